// The CLI harness itself: when it cannot start the program (no such file,
// not executable, a working folder that is not there), the test must fail
// as a set-up failure naming the path and the reason, never see an exit code
// that it would take for the program's answer.
#include "cli_harness.h"

namespace bounce::itest {
namespace {

// Options that run `program` in `tmp`; with `script`, `program` is first
// written as that shell script with permissions `perms`.
RunOptions program_in(const TempDir& tmp, const std::string& program,
                      const std::string& script = "", fs::perms perms = fs::perms::none) {
  if (!script.empty()) {
    write_text(tmp / program, script);
    fs::permissions(tmp / program, perms);
  }
  RunOptions o;
  o.cwd = tmp.path();
  o.program = tmp / program;
  return o;
}

// The harness's message when it cannot start the program.
std::string start_failure(const RunOptions& options) {
  try {
    const RunResult r = run({"--version"}, options);
    return "started, " + testing::PrintToString(r.exit_code);
  } catch (const HarnessError& e) {
    return e.what();
  }
}

TEST(Harness, MissingProgramIsAHarnessErrorNamingItAndErrno) {
  TempDir tmp;
  EXPECT_EQ(start_failure(program_in(tmp, "no-such-bounce")),
            "cannot exec " + (tmp / "no-such-bounce").string() + ": No such file or directory");
}

TEST(Harness, ProgramWithoutExecuteBitIsAHarnessError) {
  // No execute bit at all: execve refuses it even to root.
  TempDir tmp;
  const RunOptions o = program_in(tmp, "bounce", "#!/bin/sh\nexit 0\n",
                                  fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(start_failure(o), "cannot exec " + (tmp / "bounce").string() + ": Permission denied");
}

TEST(Harness, MissingWorkingFolderIsAHarnessError) {
  TempDir tmp;
  RunOptions o;
  o.cwd = tmp / "gone";
  EXPECT_EQ(start_failure(o),
            "cannot chdir to " + (tmp / "gone").string() + ": No such file or directory");
}

TEST(Harness, ProgramThatStartsReportsItsOwnExitCode) {
  // The other side: a program that starts and exits 127 itself is an
  // answer, not a harness failure.
  TempDir tmp;
  const RunOptions o = program_in(tmp, "exits-127", "#!/bin/sh\nexit 127\n", fs::perms::owner_all);
  EXPECT_EQ(run({}, o).exit_code, 127);
}

}  // namespace
}  // namespace bounce::itest
