// Outside Modbus masters nobody here wrote talk to the virtual F4 through a real pseudo-terminal:
// libmodbus's C API in-process and the mbpoll program as a child process.
#include <modbus.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "rig_sim/device_host.h"
#include "rig_sim/watlow_f4_device.h"

namespace adahrs::rig_sim {
namespace {

// 200 simulated seconds per wall second: 6 simulated minutes of heating take 1.8 s of wall time.
constexpr double kTimeScale = 200.0;

void WaitForSimulatedTime(const DeviceHost& host, double until_s) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (host.now_s() < until_s && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_GE(host.now_s(), until_s) << "the rig fell behind the scaled clock";
}

std::string RunCommand(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen((command + " 2>&1").c_str(), "r"), ::pclose);
  std::string output;
  char buffer[256];
  while (pipe && std::fgets(buffer, sizeof buffer, pipe.get()) != nullptr) output += buffer;
  return output;
}

// mbpoll prints a read register as "[100]: \t250"; returns the value or -1.
long MbpollValue(const std::string& output, int reg) {
  char label[16];
  const int label_length = std::snprintf(label, sizeof label, "[%d]:", reg);
  const size_t at = output.find(label);
  if (at == std::string::npos) return -1;
  char* end = nullptr;
  const char* start = output.c_str() + at + label_length;
  const long value = std::strtol(start, &end, 10);
  return end == start ? -1 : value;
}

TEST(WatlowF4Clients, LibmodbusReadsPvWritesTheSetPointAndSeesException03) {
  DeviceHost host(kTimeScale);
  const std::string path = host.Add(std::make_unique<WatlowF4Device>(WatlowF4DeviceConfig{}));
  host.Start();
  modbus_t* ctx = modbus_new_rtu(path.c_str(), 9600, 'N', 8, 1);
  ASSERT_NE(ctx, nullptr);
  ASSERT_EQ(modbus_set_slave(ctx, 1), 0);
  ASSERT_EQ(modbus_connect(ctx), 0) << modbus_strerror(errno);
  modbus_set_response_timeout(ctx, 2, 0);

  uint16_t pv = 0;
  ASSERT_EQ(modbus_read_registers(ctx, 100, 1, &pv), 1) << modbus_strerror(errno);
  // 25.0 °C in tenths, within the chamber's ±0.3 °C residual control cycling.
  EXPECT_NEAR(static_cast<int16_t>(pv), 250, 3);

  ASSERT_EQ(modbus_write_register(ctx, 300, 850), 1) << modbus_strerror(errno);
  const double written_s = host.now_s();
  uint16_t sp = 0;
  ASSERT_EQ(modbus_read_registers(ctx, 300, 1, &sp), 1);
  EXPECT_EQ(sp, 850);

  // 200.0 °C is beyond the 180.0 °C high limit (603): exception 03, seen as EMBXILVAL.
  errno = 0;
  EXPECT_EQ(modbus_write_register(ctx, 300, 2000), -1);
  EXPECT_EQ(errno, EMBXILVAL) << modbus_strerror(errno);

  // The chamber heats at its 5 °C/min capacity: about 55 °C six simulated minutes later. The
  // window allows for the simulated time that passes while the read itself is under way.
  WaitForSimulatedTime(host, written_s + 360.0);
  ASSERT_EQ(modbus_read_registers(ctx, 100, 1, &pv), 1) << modbus_strerror(errno);
  EXPECT_GT(static_cast<int16_t>(pv), 549);
  EXPECT_LT(static_cast<int16_t>(pv), 600);

  modbus_close(ctx);
  modbus_free(ctx);
  host.Stop();
}

TEST(WatlowF4Clients, MbpollReadsPvAndWritesTheSetPointAndTheChamberMoves) {
  DeviceHost host(kTimeScale);
  const std::string path = host.Add(std::make_unique<WatlowF4Device>(WatlowF4DeviceConfig{}));
  host.Start();
  // RTU at the F4's 9600 8N1 (shared/protocols.md §2.1), slave 1, PDU addressing (-0), holding
  // registers (-t 4), one poll (-1), 2 s timeout.
  const std::string mbpoll = "mbpoll -m rtu -a 1 -b 9600 -P none -0 -1 -o 2 -t 4 ";

  const std::string first = RunCommand(mbpoll + "-r 100 " + path);
  const long pv_before = MbpollValue(first, 100);
  EXPECT_NEAR(pv_before, 250, 3) << first;

  const std::string wrote = RunCommand(mbpoll + "-r 300 " + path + " 450");
  EXPECT_NE(wrote.find("Written 1 references"), std::string::npos) << wrote;
  const double written_s = host.now_s();
  EXPECT_EQ(MbpollValue(RunCommand(mbpoll + "-r 300 " + path), 300), 450);

  // 20 °C up at 5 °C/min is 4 min at capacity; after 10 simulated minutes the air is within the
  // exponential tail (tau 120 s from 10 °C away: 10·e^(−(600−120)/120) ≈ 0.2 °C) of 45 °C.
  WaitForSimulatedTime(host, written_s + 600.0);
  const std::string later = RunCommand(mbpoll + "-r 100 " + path);
  EXPECT_NEAR(MbpollValue(later, 100), 450, 6) << later;
  host.Stop();
}

}  // namespace
}  // namespace adahrs::rig_sim
