#include "calib/report/constant_names.h"

#include <array>
#include <sstream>
#include <vector>

#include "common/imu_layout.h"

namespace adahrs::calib {
namespace {

constexpr std::array<const char*, 3> kAxes = {"x", "y", "z"};
constexpr std::array<const char*, 3> kThermometers = {"tx", "ty", "tz"};

std::vector<std::string> Split(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  std::string part;
  while (std::getline(in, part, '/')) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

bool IsIndex(const std::string& s, size_t size) {
  if (s.empty() || s.size() > 2 || s.find_first_not_of("0123456789") != std::string::npos) {
    return false;
  }
  return static_cast<size_t>(std::stoi(s)) < size;
}

template <size_t N>
std::string Name(const std::array<const char*, N>& names, const std::string& index) {
  return names[static_cast<size_t>(std::stoi(index))];
}

// "k/1" -> "k1"; "offset_duty" -> "offset_duty".
std::string Term(const std::vector<std::string>& p, size_t from) {
  std::string term;
  for (size_t i = from; i < p.size(); ++i) term += p[i];
  return term;
}

std::string Matrix(const char* name,
                   const std::array<const char*, 3>& rows,
                   const std::string& r,
                   const std::string& c) {
  return std::string(name) + "[" + Name(rows, r) + "][" + Name(kAxes, c) + "]";
}

}  // namespace

std::string ImuConstantName(const std::string& json_path) {
  const std::vector<std::string> p = Split(json_path);
  if (p.size() >= 3 && IsIndex(p[1], 9) && p[0] == "thermal") {
    return "thermal " + Name(common::kImuChannelNames, p[1]) + " " + Term(p, 2);
  }
  if (p.size() >= 3 && IsIndex(p[1], 6) && p[0] == "accel") {
    return "accel " + Name(common::kAccelChannelNames, p[1]) + " " + Term(p, 2);
  }
  if (p.size() >= 3 && IsIndex(p[1], 3) && p[0] == "gyro") {
    return "gyro " + Name(common::kGyroChannelNames, p[1]) + " " + Term(p, 2);
  }
  if (p.size() == 3 && IsIndex(p[1], 3) && IsIndex(p[2], 3)) {
    if (p[0] == "ca_mps2_per_g") return Matrix("CA", kAxes, p[1], p[2]);
    if (p[0] == "cg") return Matrix("CG", kAxes, p[1], p[2]);
  }
  if (p.size() >= 3 && p[0] == "scale_temperature") {
    if (p[1] == "scale" && IsIndex(p[2], 9) && p.size() == 4) {
      return "scale factor " + Name(common::kImuChannelNames, p[2]) + " term " + p[3];
    }
    if (p[1] == "sensor" && IsIndex(p[2], 3) && p.size() == 4) {
      return "scale temperature " + Name(kThermometers, p[2]) + " " + p[3];
    }
    if (p[1] == "accel_quadratic_per_g" && IsIndex(p[2], 3) && p.size() == 3) {
      return "accel quadratic " + Name(kAxes, p[2]);
    }
    if (p[1] == "gs_dps_per_mps2" && p.size() == 4 && IsIndex(p[2], 3) && IsIndex(p[3], 3)) {
      return Matrix("GS", common::kGyroChannelNames, p[2], p[3]);
    }
  }
  return json_path;
}

}  // namespace adahrs::calib
