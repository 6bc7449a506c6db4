#include "hil/transport/serial_port.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hil/transport/pty.h"

namespace adahrs::hil {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using namespace std::chrono_literals;

std::string ReadMaster(int fd, size_t count) {
  std::string out;
  char buf[256];
  for (int i = 0; i < 200 && out.size() < count; ++i) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0)
      out.append(buf, static_cast<size_t>(n));
    else
      std::this_thread::sleep_for(1ms);
  }
  return out;
}

TEST(SerialPort, TalksThroughAPtyBothWays) {
  PtyPair pty = PtyPair::Open();
  SerialPort port({pty.slave_path(), 9600}, "rate_table");
  port.Write("JOG 100\r\n", 500ms);
  EXPECT_EQ(ReadMaster(pty.master_fd(), 9), "JOG 100\r\n");
  const std::string reply = "\r\n>\r\nextra";
  ASSERT_EQ(::write(pty.master_fd(), reply.data(), reply.size()), ssize_t(reply.size()));
  EXPECT_EQ(port.ReadUntil(">\r\n", 1000ms), "\r\n>\r\n");
  // Bytes after the terminator are kept for the next read.
  EXPECT_EQ(port.ReadExactly(5, 1000ms), std::vector<uint8_t>({'e', 'x', 't', 'r', 'a'}));
}

TEST(SerialPort, TimeoutNamesRolePortAndWhatArrived) {
  PtyPair pty = PtyPair::Open();
  SerialPort port({pty.slave_path(), 9600}, "chamber");
  ASSERT_EQ(::write(pty.master_fd(), "\x01\x03", 2), 2);
  try {
    port.ReadUntil("\r\n", 100ms);
    FAIL();
  } catch (const TransportTimeout& e) {
    EXPECT_THAT(e.what(),
                AllOf(HasSubstr("chamber"),
                      HasSubstr(pty.slave_path()),
                      HasSubstr("0D 0A"),
                      HasSubstr("01 03"),
                      HasSubstr("100 ms")));
  }
  uint8_t buf[8];
  EXPECT_EQ(port.ReadSome(buf, 50ms), 0u);  // a poll with nothing pending is not an error
}

TEST(SerialPort, TraceSeesEveryByte) {
  PtyPair pty = PtyPair::Open();
  SerialPort port({pty.slave_path(), 115200}, "imu1");
  std::string sent, received;
  port.SetTrace([&](TraceDirection d, std::span<const uint8_t> bytes) {
    (d == TraceDirection::kSent ? sent : received).append(bytes.begin(), bytes.end());
  });
  port.Write("ab", 500ms);
  ASSERT_EQ(::write(pty.master_fd(), "xyz", 3), 3);
  port.ReadExactly(3, 1000ms);
  EXPECT_EQ(sent, "ab");
  EXPECT_EQ(received, "xyz");
}

TEST(SerialPort, MissingDeviceIsAClearError) {
  try {
    SerialPort port({"/dev/does-not-exist-adahrs", 9600}, "adts");
    FAIL();
  } catch (const TransportError& e) {
    EXPECT_THAT(
        e.what(),
        AllOf(
            HasSubstr("adts"), HasSubstr("/dev/does-not-exist-adahrs"), HasSubstr("cannot open")));
  }
}

// pyserial's exclusive open (flock LOCK_EX | LOCK_NB, as ours): 0 when it got the port, 3 when
// refused, another status when it could not run.
int PyserialExclusiveOpen(const std::string& path) {
  const std::string command =
      "/usr/bin/python3 -c 'import sys, serial\n"
      "try:\n    serial.Serial(sys.argv[1], exclusive=True).close()\n"
      "except serial.SerialException:\n    sys.exit(3)' " +
      path;
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SerialPort, ASecondExclusiveOpenIsRefusedByAnyPathUntilTheFirstCloses) {
  PtyPair pty = PtyPair::Open();
  const std::string link = ::testing::TempDir() + "adahrs-port-link-" + std::to_string(::getpid());
  std::filesystem::remove(link);
  std::filesystem::create_symlink(pty.slave_path(), link);
  {
    SerialPort first({pty.slave_path(), 9600}, "imu1");
    for (const std::string& path : {pty.slave_path(), link}) {
      try {
        SerialPort second({path, 9600}, "imu2");
        FAIL() << "opened twice through " << path;
      } catch (const TransportError& e) {
        EXPECT_THAT(e.what(), AllOf(HasSubstr("imu2"), HasSubstr(path), HasSubstr("in use")));
      }
    }
    EXPECT_EQ(PyserialExclusiveOpen(pty.slave_path()), 3) << "an independent client got the port";
    SerialPort shared({pty.slave_path(), 9600}, "operator", PortAccess::kShared);
  }
  EXPECT_EQ(PyserialExclusiveOpen(link), 0);
  SerialPort again({link, 9600}, "imu1");
  std::filesystem::remove(link);
}

TEST(SerialPort, HexBytesTruncatesLongDumps) {
  std::vector<uint8_t> bytes(100, 0xAB);
  EXPECT_THAT(HexBytes(bytes, 4), AllOf(HasSubstr("AB AB AB AB"), HasSubstr("100 bytes")));
}

// An instrument on software flow control (the Watlow 942) sends XOFF when a line arrives and XON
// when it has processed it. Discarding input just as the XON arrives must not lose it: a lost XON
// leaves the PC's output stopped and the next command's write times out. Without the read-based
// discard, tcflush drops the XON in about a quarter of these rounds on a 2-core VM.
TEST(SerialPort, DiscardingInputKeepsAnInstrumentsXon) {
  PtyPair pty = PtyPair::Open();
  SerialSettings settings{pty.slave_path(), 9600};
  settings.flow = SerialSettings::Flow::kSoftware;
  SerialPort port(settings, "ads_chamber");
  const char xoff = 0x13;
  const char xon = 0x11;
  for (int round = 0; round < 300; ++round) {
    ASSERT_EQ(::write(pty.master_fd(), &xoff, 1), 1);
    std::this_thread::sleep_for(200us);  // the line discipline has stopped the output
    ASSERT_EQ(::write(pty.master_fd(), &xon, 1), 1);
    port.DiscardInput();
    ASSERT_NO_THROW(port.Write("? ER2\r", 1000ms)) << "round " << round;
    ASSERT_EQ(ReadMaster(pty.master_fd(), 6), "? ER2\r") << "round " << round;
  }
}

}  // namespace
}  // namespace adahrs::hil
