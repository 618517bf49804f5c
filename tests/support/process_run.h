#pragma once
// Running one of our programs as a user would, for the CLI and window tests: a
// real process through the shell, its output captured in files, its exit code.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace neurocloth::test {

struct Outcome {
  int code = -1;  // -1: did not exit normally; 124: killed by the timeout
  std::string out, err;
};

// `s` as one shell word.
inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `prelude` then `program args...` in one shell; a run that outlives
// `timeout_seconds` is killed and reported as exit code 124, so a hang fails
// the test instead of stalling the suite. stdout and stderr go to files in
// `dir` (stdout.txt, stderr.txt) and come back in the Outcome.
inline Outcome run_process(const std::string& prelude, const std::string& program,
                           const std::vector<std::string>& args, int timeout_seconds,
                           const std::filesystem::path& dir) {
  std::string cmd =
      prelude + "timeout -k 5 " + std::to_string(timeout_seconds) + " " + quote(program);
  for (const auto& a : args)
    cmd += " " + quote(a);
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  cmd += " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(cmd.c_str());
  Outcome r;
  if (status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

}  // namespace neurocloth::test
