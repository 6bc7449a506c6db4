// Reads or writes a SQLite database with Python's own sqlite3 module (/usr/bin/python3): an
// independent client of what the records code wrote. Returns what the statement printed (the
// rows' repr, or SQLite's error message) and the exit status (0, or 3 when SQLite refused it).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

namespace adahrs::testing {

inline std::pair<std::string, int> PythonSqlite(const std::filesystem::path& db,
                                                const std::string& sql,
                                                const std::filesystem::path& scratch_dir) {
  const auto script = scratch_dir / "python_sqlite.py";
  std::ofstream(script) << "import sqlite3, sys\n"
                        << "c = sqlite3.connect(sys.argv[1])\n"
                        << "try:\n"
                        << "    print(repr(c.execute(sys.argv[2]).fetchall())); c.commit()\n"
                        << "except sqlite3.Error as e:\n"
                        << "    print(e); sys.exit(3)\n";
  const std::string command =
      std::string(ADAHRS_PYTHON) + " " + script.string() + " " + db.string() + " \"" + sql + "\"";
  FILE* pipe = ::popen(command.c_str(), "r");
  std::string out;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = ::pclose(pipe);
  return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

}  // namespace adahrs::testing
