#include "hil/drivers/watlow_f4_chamber.h"

#include <thread>

#include <modbus.h>

#include <cerrno>
#include <cmath>
#include <variant>

#include <fmt/format.h>

#include "hil/drivers/instrument_port.h"

namespace adahrs::hil {
namespace {

using Kind = InstrumentError::Kind;

// Registers (shared/protocols.md §2.3-2.4, DRV).
constexpr uint16_t kRegSave = 25;
constexpr uint16_t kRegProcessValue = 100;
constexpr uint16_t kRegProfileState = 200;
constexpr uint16_t kRegStaticSetPoint = 300;
constexpr uint16_t kRegDecimals = 606;
constexpr uint16_t kRegUnits = 901;
constexpr uint16_t kRegTerminate = 1217;
constexpr uint16_t kRegNameFirst = 3500;
constexpr int kNameChars = 10;
constexpr int kProfiles = 40;
constexpr uint16_t kRegProfile = 4000;
constexpr uint16_t kRegStep = 4001;
constexpr uint16_t kRegEditAction = 4002;
constexpr uint16_t kRegStepType = 4003;
constexpr uint16_t kRegHours = 4009;
constexpr uint16_t kRegRampRate = 4043;
constexpr uint16_t kRegTarget = 4044;
constexpr uint16_t kRegJumpProfile = 4050;
constexpr uint16_t kRegEndAction = 4060;
constexpr uint16_t kRegIdleSetPoint = 4061;
constexpr uint16_t kRegCurrentSetPoint = 4122;
// Values.
constexpr uint16_t kUnitsCelsius = 1;
constexpr uint16_t kStateRunning = 2;
constexpr uint16_t kStateHolding = 3;
constexpr uint16_t kCreateProfile = 1;
constexpr uint16_t kInsertStep = 2;
constexpr uint16_t kDeleteProfile = 3;
constexpr uint16_t kRunProfile = 5;
constexpr uint16_t kStepRampTime = 1;
constexpr uint16_t kStepRampRate = 2;
constexpr uint16_t kStepSoak = 3;
constexpr uint16_t kStepJump = 4;
constexpr uint16_t kStepEnd = 5;
constexpr uint16_t kStepMissing = 6;  // 4003 of a profile that does not exist (ChamberConnect)
// Per-read register limit of the F4 (protocols.md §2.1: ≥ 60 seen; 125 the Modbus limit).
constexpr int kMaxReadRegisters = 100;

std::string ExceptionName(int code) {
  switch (code) {
    case 1:
      return "illegal function";
    case 2:
      return "illegal data address";
    case 3:
      return "illegal data value";
    case 4:
      return "slave device failure";
    default:
      return "exception";
  }
}

uint16_t EndActionCode(F4EndAction action) {
  switch (action) {
    case F4EndAction::kHold:
      return 0;
    case F4EndAction::kControlOff:
      return 1;
    case F4EndAction::kAllOff:
      return 2;
    case F4EndAction::kIdle:
      return 3;
  }
  return 0;
}

}  // namespace

WatlowF4Chamber::WatlowF4Chamber(const InstrumentEntry& entry, const Clock& clock)
    : entry_(entry), clock_(clock) {
  const SerialSettings& s = entry.port;
  ctx_ = modbus_new_rtu(s.path.c_str(),
                        static_cast<int>(s.baud),
                        s.parity,
                        static_cast<int>(s.data_bits),
                        static_cast<int>(s.stop_bits));
  if (ctx_ == nullptr) Fail(Kind::kNoReply, "open", "", modbus_strerror(errno));
  if (modbus_set_slave(ctx_, entry.address) != 0 || modbus_connect(ctx_) != 0) {
    const std::string why = modbus_strerror(errno);
    modbus_free(ctx_);
    ctx_ = nullptr;
    Fail(Kind::kNoReply, "open", "", why);
  }
  const auto timeout = WallReplyTimeout(clock_, entry.timeout_ms);
  const auto seconds = static_cast<uint32_t>(timeout.count() / 1000);
  const auto micros = static_cast<uint32_t>((timeout.count() % 1000) * 1000);
  modbus_set_response_timeout(ctx_, seconds, micros);
  modbus_set_byte_timeout(ctx_, seconds, micros);
}

WatlowF4Chamber::~WatlowF4Chamber() {
  if (ctx_ != nullptr) {
    modbus_close(ctx_);
    modbus_free(ctx_);
  }
}

void WatlowF4Chamber::Fail(Kind kind,
                           const std::string& command,
                           const std::string& reply,
                           const std::string& detail) const {
  throw InstrumentError(kind, entry_.role, entry_.port.path, command, reply, detail);
}

template <typename Call>
void WatlowF4Chamber::Transact(const std::string& command, Call call) {
  // A garbled or stale reply (a crashed predecessor's late answers, line noise) is flushed and the
  // transaction repeated like a missing one: every register read and write here is idempotent.
  const int attempts = entry_.retries + 1;
  std::string last_error;
  bool last_was_timeout = true;
  const std::chrono::milliseconds wall_timeout = WallReplyTimeout(clock_, entry_.timeout_ms);
  const auto started = std::chrono::steady_clock::now();
  for (int attempt = 0; attempt < attempts; ++attempt) {
    const ReplyDeadline deadline(clock_, entry_.timeout_ms / 1000.0, wall_timeout);
    errno = 0;
    if (call() >= 0) return;
    const int error = errno;
    if (error == ETIMEDOUT && !deadline.Passed() &&
        std::chrono::steady_clock::now() - started < kMaxReplyWall) {
      // libmodbus gave up on the wall clock while the rig's clock stood still (a lockstep rig
      // held for a slow reader): the controller has not yet had its time. Wait until it has,
      // drop whatever late answer came, and ask again without counting the attempt.
      while (!deadline.Passed()) std::this_thread::sleep_for(deadline.WaitLeft());
      modbus_flush(ctx_);
      --attempt;
      continue;
    }
    if (error > MODBUS_ENOBASE && error <= MODBUS_ENOBASE + MODBUS_EXCEPTION_GATEWAY_TARGET) {
      const int code = error - MODBUS_ENOBASE;
      Fail(Kind::kRefused,
           command,
           fmt::format("exception {:02d} ({})", code, ExceptionName(code)),
           "Modbus exception");
    }
    last_error = modbus_strerror(error);
    last_was_timeout = error == ETIMEDOUT;
    modbus_flush(ctx_);
  }
  if (!last_was_timeout) {
    Fail(Kind::kBadReply, command, "", fmt::format("{} after {} attempts", last_error, attempts));
  }
  Fail(Kind::kNoReply,
       command,
       "",
       fmt::format("{} attempts of {} ms wall each",
                   attempts,
                   WallReplyTimeout(clock_, entry_.timeout_ms).count()));
}

std::vector<uint16_t> WatlowF4Chamber::Read(uint16_t reg, int count) {
  std::vector<uint16_t> values(static_cast<size_t>(count));
  Transact(fmt::format("read register {} (x{})", reg, count),
           [&] { return modbus_read_registers(ctx_, reg, count, values.data()); });
  return values;
}

void WatlowF4Chamber::Write(uint16_t reg, uint16_t value) {
  Transact(fmt::format("write register {} = {}", reg, static_cast<int16_t>(value)),
           [&] { return modbus_write_register(ctx_, reg, value); });
}

void WatlowF4Chamber::WriteMany(uint16_t reg, const std::vector<uint16_t>& values) {
  Transact(fmt::format("write registers {}..{}", reg, reg + values.size() - 1), [&] {
    return modbus_write_registers(ctx_, reg, static_cast<int>(values.size()), values.data());
  });
}

int WatlowF4Chamber::Decimals() {
  if (decimals_ < 0) {
    const uint16_t decimals = Read(kRegDecimals, 1)[0];
    if (decimals > 3) {
      Fail(
          Kind::kBadReply, "read register 606", std::to_string(decimals), "decimals 0..3 expected");
    }
    decimals_ = decimals;
  }
  return decimals_;
}

uint16_t WatlowF4Chamber::ToRegister(double temp_c, const std::string& what) {
  const double scaled = std::round(temp_c * std::pow(10.0, Decimals()));
  if (scaled < -32768.0 || scaled > 32767.0) {
    Fail(Kind::kRefused, what, "", fmt::format("{} degC does not fit a register", temp_c));
  }
  return static_cast<uint16_t>(static_cast<int16_t>(scaled));
}

double WatlowF4Chamber::FromRegister(uint16_t value) {
  return static_cast<int16_t>(value) / std::pow(10.0, Decimals());
}

InstrumentIdentity WatlowF4Chamber::Identify() {
  const uint16_t units = Read(kRegUnits, 1)[0];
  if (units != kUnitsCelsius) {
    Fail(Kind::kWrongIdentity,
         "read register 901",
         std::to_string(units),
         "the controller does not work in degC (901 = 1)");
  }
  return {
      "Watlow F4",
      fmt::format("Modbus address {}, {} implied decimal(s), degC", entry_.address, Decimals())};
}

void WatlowF4Chamber::SetSetPointC(double temp_c) {
  Write(kRegStaticSetPoint, ToRegister(temp_c, "write register 300"));
}

double WatlowF4Chamber::ReadSetPointC() { return FromRegister(Read(kRegCurrentSetPoint, 1)[0]); }

double WatlowF4Chamber::ReadProcessC() {
  const std::vector<uint16_t> values = Read(kRegProcessValue, 2);
  if (values[1] != 0) {
    Fail(Kind::kFault, "read register 101", std::to_string(values[1]), "input 1 error");
  }
  return FromRegister(values[0]);
}

void WatlowF4Chamber::Hold() {
  const uint16_t state = Read(kRegProfileState, 1)[0];
  if (state != kStateRunning && state != kStateHolding) return;  // static: already holding
  const uint16_t set_point = Read(kRegCurrentSetPoint, 1)[0];
  Write(kRegTerminate, 1);
  Write(kRegStaticSetPoint, set_point);
}

std::vector<int> WatlowF4Chamber::FindProfiles(const std::string& padded_name) {
  std::vector<uint16_t> names;
  for (int first = 0; first < kProfiles * kNameChars; first += kMaxReadRegisters) {
    const std::vector<uint16_t> part =
        Read(static_cast<uint16_t>(kRegNameFirst + first), kMaxReadRegisters);
    names.insert(names.end(), part.begin(), part.end());
  }
  std::vector<int> found;
  for (int n = 1; n <= kProfiles; ++n) {
    std::string name;
    for (int i = 0; i < kNameChars; ++i) {
      name += static_cast<char>(names[static_cast<size_t>((n - 1) * kNameChars + i)]);
    }
    if (name != padded_name) continue;
    WriteMany(kRegProfile, {static_cast<uint16_t>(n), 1});
    if (Read(kRegStepType, 1)[0] != kStepMissing) found.push_back(n);
  }
  return found;
}

void WatlowF4Chamber::DownloadProfile(const std::string& name,
                                      const std::vector<F4ProfileStep>& steps) {
  const std::string command = "download profile " + name;
  std::string padded;
  for (const char c : name) {
    const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (!((u >= 'A' && u <= 'Z') || (u >= '0' && u <= '9') || u == ' ')) {
      Fail(Kind::kRefused, command, "", "a profile name holds A-Z, 0-9 and spaces only");
    }
    padded += u;
  }
  if (padded.empty() || padded.size() > kNameChars) {
    Fail(Kind::kRefused, command, "", "a profile name has 1 to 10 characters");
  }
  padded.resize(kNameChars, ' ');
  if (steps.empty() || !std::holds_alternative<F4End>(steps.back())) {
    Fail(Kind::kRefused, command, "", "the last step must be an end step");
  }
  for (size_t i = 0; i + 1 < steps.size(); ++i) {
    if (std::holds_alternative<F4End>(steps[i])) {
      Fail(Kind::kRefused,
           command,
           "",
           fmt::format("step {} is an end step before the last", i + 1));
    }
  }

  for (const int old : FindProfiles(padded)) {
    WriteMany(kRegProfile, {static_cast<uint16_t>(old), 1, kDeleteProfile});
    WriteMany(static_cast<uint16_t>(kRegNameFirst + kNameChars * (old - 1)),
              std::vector<uint16_t>(kNameChars, ' '));
  }
  Write(kRegEditAction, kCreateProfile);
  const uint16_t number = Read(kRegProfile, 1)[0];
  WriteMany(static_cast<uint16_t>(kRegNameFirst + kNameChars * (number - 1)),
            std::vector<uint16_t>(padded.begin(), padded.end()));

  const auto duration = [&](double duration_s, size_t index) {
    const long total_s = std::lround(duration_s);
    if (duration_s < 0 || total_s > 99 * 3600 + 59 * 60 + 59) {
      Fail(Kind::kRefused,
           command,
           "",
           fmt::format("step {}: {} s is outside 0..99:59:59", index + 1, duration_s));
    }
    return std::vector<uint16_t>{static_cast<uint16_t>(total_s / 3600),
                                 static_cast<uint16_t>(total_s / 60 % 60),
                                 static_cast<uint16_t>(total_s % 60)};
  };
  for (size_t i = 0; i + 1 < steps.size(); ++i) {
    const auto step_number = static_cast<uint16_t>(i + 1);
    WriteMany(kRegStep, {step_number, kInsertStep});
    const F4ProfileStep& step = steps[i];
    if (const auto* ramp = std::get_if<F4RampTime>(&step)) {
      Write(kRegStepType, kStepRampTime);
      WriteMany(kRegHours, duration(ramp->duration_s, i));
      Write(kRegTarget, ToRegister(ramp->target_c, command));
    } else if (const auto* rate = std::get_if<F4RampRate>(&step)) {
      Write(kRegStepType, kStepRampRate);
      Write(kRegRampRate, static_cast<uint16_t>(std::lround(rate->rate_c_per_min * 10.0)));
      Write(kRegTarget, ToRegister(rate->target_c, command));
    } else if (const auto* soak = std::get_if<F4Soak>(&step)) {
      Write(kRegStepType, kStepSoak);
      WriteMany(kRegHours, duration(soak->duration_s, i));
    } else if (const auto* jump = std::get_if<F4Jump>(&step)) {
      Write(kRegStepType, kStepJump);
      WriteMany(kRegJumpProfile,
                {number, static_cast<uint16_t>(jump->to_step), static_cast<uint16_t>(jump->count)});
    }
  }
  const F4End& end = std::get<F4End>(steps.back());
  Write(kRegStep, static_cast<uint16_t>(steps.size()));
  Write(kRegStepType, kStepEnd);
  Write(kRegEndAction, EndActionCode(end.action));
  if (end.action == F4EndAction::kIdle) Write(kRegIdleSetPoint, ToRegister(end.idle_c, command));
  Write(kRegSave, 0);
  profile_numbers_[padded] = number;
}

void WatlowF4Chamber::StartProfile(const std::string& name) {
  std::string padded;
  for (const char c : name)
    padded += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  padded.resize(kNameChars, ' ');
  int number = 0;
  if (const auto known = profile_numbers_.find(padded); known != profile_numbers_.end()) {
    number = known->second;
  } else {
    const std::vector<int> found = FindProfiles(padded);
    if (found.empty()) Fail(Kind::kRefused, "start profile " + name, "", "no profile of that name");
    number = found.front();
  }
  Write(kRegProfile, static_cast<uint16_t>(number));
  Write(kRegStep, 1);
  Write(kRegEditAction, kRunProfile);
}

bool WatlowF4Chamber::ProfileRunning() {
  const uint16_t state = Read(kRegProfileState, 1)[0];
  return state == kStateRunning || state == kStateHolding;
}

}  // namespace adahrs::hil
