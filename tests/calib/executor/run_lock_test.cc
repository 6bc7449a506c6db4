// One process per run directory: a second lock is refused naming the holder's pid, and the lock
// is free again once its holder is gone (as when the holding process ends).
#include "calib/executor/run_lock.h"

#include <unistd.h>

#include <optional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/executor/executor.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

TEST(RunDirectoryLock, ASecondHolderIsRefusedUntilTheFirstIsGone) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adahrs_run_lock_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::optional<RunDirectoryLock> first(std::in_place, dir);
  try {
    RunDirectoryLock second(dir);
    FAIL() << "two holders";
  } catch (const RunError& e) {
    EXPECT_THAT(e.what(),
                AllOf(HasSubstr(dir.string()),
                      HasSubstr("in use by another adahrs process"),
                      HasSubstr("(pid " + std::to_string(::getpid()) + ")")));
  }
  first.reset();
  EXPECT_NO_THROW(RunDirectoryLock again(dir));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::calib
