// Real outside clients (pyserial, as pyvisa-py and a terminal program use the port) talk to the
// ADS bench instruments through pseudo-terminals served by DeviceHost.
#include <cstdio>
#include <string>
#include "adahrs_build_paths.h"

#include <gtest/gtest.h>

#include "rig_sim/device_host.h"
#include "rig_sim/prologix_adts_device.h"
#include "rig_sim/watlow_942_device.h"

namespace adahrs::rig_sim {
namespace {

std::string RunClient(const std::string& script, const std::string& port) {
  const std::string command = std::string(ADAHRS_PYTHON) + " " + ADAHRS_SOURCE_DIR +
                              "/tests/rig_sim/clients/" + script + " " + port + " 2>&1";
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return "<popen failed>";
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  ::pclose(pipe);
  return output;
}

TEST(AdsBenchPty, PyvisaStylePrologixSessionGetsAdtsAnswers) {
  DeviceHost host(1.0);
  const nlohmann::json config = DefaultPrologixAdtsConfig();
  const std::string path = host.Add(MakePrologixAdtsDevice(common::ParamReader(config, "default")));
  host.Start();
  const std::string output = RunClient("adts_pyvisa_session.py", path);
  host.Stop();
  EXPECT_EQ(output,
            "Prologix GPIB-USB Controller version 6.107\n"
            "DRUCK,ADTS405,0000000,V1.00\n"
            "ON\n"
            "|ALT| < 5 ft: True\n");
}

TEST(AdsBenchPty, PyserialXonXoffSessionSpeaks942) {
  DeviceHost host(1.0);
  const nlohmann::json config = DefaultWatlow942Config();
  const std::string path = host.Add(MakeWatlow942Device(common::ParamReader(config, "default")));
  host.Start();
  const std::string output = RunClient("watlow942_session.py", path);
  host.Stop();
  EXPECT_EQ(output, "40.0\n0\n25\n942 1\n");
}

}  // namespace
}  // namespace adahrs::rig_sim
