// The typed error every instrument and unit driver throws: which instrument (role and port), which
// command, and what came back (or that nothing did). The executor turns it into the message that
// stops a run ("rate_table on /dev/ttyS0: JOG 200: replied 'ERR 3 out of range'"). The command,
// the reply and the detail are quoted as common::PrintableText (a CR shows as \r).
#pragma once

#include <stdexcept>
#include <string>

namespace adahrs::hil {

class InstrumentError : public std::runtime_error {
 public:
  enum class Kind {
    kNoReply,   ///< nothing (or nothing complete) came back within the timeout, after retries
    kRefused,   ///< the instrument answered with an error (Modbus exception, ATL/942/SCPI error)
    kBadReply,  ///< a reply that does not parse as the command's answer
    kWrongIdentity,  ///< the port answers, but as another instrument or unit
    kFault,          ///< the instrument reports a fault state (interlock open, sensor break)
  };

  InstrumentError(Kind kind,
                  std::string role,
                  std::string port,
                  std::string command,
                  std::string reply,
                  const std::string& detail);

  Kind kind() const { return kind_; }
  const std::string& role() const { return role_; }
  const std::string& port() const { return port_; }
  const std::string& command() const { return command_; }
  /// What came back, as PrintableText (binary protocols pass hex); empty when nothing did.
  const std::string& reply() const { return reply_; }

 private:
  Kind kind_;
  std::string role_;
  std::string port_;
  std::string command_;
  std::string reply_;
};

const char* ToString(InstrumentError::Kind kind);

}  // namespace adahrs::hil
