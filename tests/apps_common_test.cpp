// The tools' shared layer (apps/common: the runner, the option checks, the atomic output) under
// hostile input, with real runs of the built executables: FIFOs, devices and sparse files as
// input, byte-order marks, coordinates of 1e308, running out of memory, options that are NaN,
// too large or negative, seeds beyond 64 bits, and outputs interrupted by signals.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "app_test_util.h"

namespace {

namespace fs = std::filesystem;
using eftest::CommandResult;

std::string q(const fs::path& p) { return eftest::shell_quoted(p.string()); }
std::string data_file(const std::string& name) { return (fs::path(EDGEFRONT_DATA_DIR) / name).string(); }
void spit(const fs::path& p, const std::string& content) { std::ofstream(p, std::ios::binary) << content; }

/// Every app's fixture: `run(app, args)` runs EDGEFRONT_APP_DIR/app in the test's directory.
class AppsCommon : public eftest::AppTest {
 protected:
  AppsCommon() : AppTest("ef-info") {}
  /// Runs the app under `timeout`: an app that blocks (on a FIFO, say) fails instead of hanging.
  CommandResult run_app(const std::string& app, const std::string& args) const {
    return eftest::run_command("timeout", "20 " + q(fs::path(EDGEFRONT_APP_DIR) / app) + " " + args, dir_);
  }
  /// Hidden temporaries of `name` in the test directory.
  std::vector<std::string> temporaries(const std::string& name) const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string f = e.path().filename().string();
      if (f.rfind("." + name + ".tmp-", 0) == 0) out.push_back(f);
    }
    return out;
  }
};

/// A run's single error line starts with "<app>: error: " and contains `part`.
void expect_error(const CommandResult& r, int code, const std::string& app, const std::string& part) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_EQ(r.err.rfind(app + ": error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(part), std::string::npos) << "expected '" << part << "' in: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// ---------------------------------------------------------------------------------------------
// Input files

TEST_F(AppsCommon, FifosAndDevicesAreRefusedByEveryReaderWithoutBlocking) {
  ASSERT_EQ(::mkfifo((dir_ / "pipe.off").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir_ / "pipe.xyz").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir_ / "zero.ply");
  const auto t0 = std::chrono::steady_clock::now();
  expect_error(run_app("ef-info", q(dir_ / "pipe.off")), 1, "ef-info", "is a FIFO (named pipe), not a regular file");
  expect_error(run_app("ef-distance", q(dir_ / "zero.ply") + " --source 0"), 1, "ef-distance",
               "is a character device, not a regular file");
  expect_error(run_app("gcs-reconstruct", q(dir_ / "pipe.xyz") + " -o " + q(dir_ / "out.ply")), 1,
               "gcs-reconstruct", "not a regular file");
  expect_error(run_app("gcs-eval", data_file("neck.off") + " " + q(dir_ / "pipe.xyz")), 1, "gcs-eval",
               "not a regular file");
  expect_error(run_app("ef-twist", data_file("neck.off") + " --points " + q(dir_ / "zero.ply") + " -o " +
                                       q(dir_ / "fixed.off")),
               1, "ef-twist", "character device");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 8.0);
  EXPECT_FALSE(fs::exists(dir_ / "out.ply"));
  EXPECT_FALSE(fs::exists(dir_ / "fixed.off"));
}

TEST_F(AppsCommon, AnObjWithAByteOrderMarkKeepsItsFirstVertex) {
  spit(dir_ / "bom.obj", "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\n");
  const CommandResult r = run(q(dir_ / "bom.obj"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4 vertices, 2 faces in file, 2 triangles added"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
}

TEST_F(AppsCommon, CoordinatesOf1e308Or1e310AreRefusedWithTheReason) {
  // A tetrahedron scaled up or down: before, ef-distance wrote inf ("unreached") and exit 0, and
  // gcs-reconstruct said "all points coincide".
  const auto tetra = [](const std::string& s) {
    return "OFF\n4 4 0\n0 0 0\n" + s + " 0 0\n0 " + s + " 0\n0 0 " + s + "\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  };
  spit(dir_ / "huge.off", tetra("1e308"));
  spit(dir_ / "tiny.off", tetra("1e-310"));
  expect_error(run_app("ef-distance", q(dir_ / "huge.off") + " --source 0"), 1, "ef-distance",
               "vertex 1 has the coordinate 1e308, beyond +-1e75: squared lengths and areas would overflow");
  expect_error(run_app("ef-distance", q(dir_ / "tiny.off") + " --source 0"), 1, "ef-distance",
               "span only 1e-310, less than 1e-75: squared lengths and areas would underflow");
  expect_error(run_app("gcs-eval", q(dir_ / "huge.off") + " " + data_file("neck.off")), 1, "gcs-eval", "overflow");
  spit(dir_ / "huge.xyz", "0 0 0 0 0 1\n1e308 0 0 0 0 1\n0 1e308 0 0 0 1\n1e308 1e308 0 0 0 1\n0 0 1 0 0 1\n");
  expect_error(run_app("gcs-reconstruct", q(dir_ / "huge.xyz") + " -o " + q(dir_ / "out.ply")), 1,
               "gcs-reconstruct", "point 1 has the coordinate 1e308");
  // An invalid normal is dropped with a warning naming why (too long, not zero-length) and refitted
  // from the neighbours; the rest of the cloud is used.
  spit(dir_ / "long_normal.xyz", "0 0 0 0 0 1\n1 0 0 1e308 1e308 0\n0 1 0 0 0 1\n1 1 0 0 0 1\n");
  const CommandResult r = run_app("gcs-reconstruct", q(dir_ / "long_normal.xyz") + " -o " + q(dir_ / "out.ply"));
  EXPECT_NE(r.err.find("gcs-reconstruct: warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line 2: normal too long"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("zero-length"), std::string::npos) << r.err;
}

// ---------------------------------------------------------------------------------------------
// Memory

TEST_F(AppsCommon, RunningOutOfMemoryNamesTheRequest) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "an address-space limit cannot be combined with AddressSanitizer's shadow memory";
#else
  // 1 GB of address space cannot hold 10^8 points (about 5 GB): a std::bad_alloc, which the
  // runner turns into a message naming --points instead of "error: std::bad_alloc".
  const std::string args = "torus --points 100000000 -o " + q(dir_ / "x.xyz");
  const std::string command = "ulimit -v 1000000; " + q(app_.parent_path() / "ef-shapes") + " " + args;
  const CommandResult r = eftest::run_command("/bin/sh", "-c " + eftest::shell_quoted(command), dir_);
  expect_error(r, 1, "ef-shapes", "--points 100000000: not enough memory for this request");
  EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.xyz"));
  EXPECT_TRUE(temporaries("x.xyz").empty());
#endif
}

// ---------------------------------------------------------------------------------------------
// Options, at parse time

TEST_F(AppsCommon, PictureOptionsAreCheckedBeforeAnyWorkOrWrite) {
  const std::string mesh = data_file("bumpy-sphere.off");
  const fs::path out = dir_ / "d.txt", png = dir_ / "d.png";
  const std::string common = mesh + " --source 0 -o " + q(out) + " --png " + q(png);
  struct Case {
    std::string args, message;
  };
  for (const Case& c : std::vector<Case>{
           {" --azimuth nan", "--azimuth: nan is not a number"},
           {" --elevation nan", "--elevation: nan is not a number"},
           {" --elevation 91", "--elevation: 91 is out of range (-90 ... 90)"},
           {" --azimuth 1e400", "--azimuth: '1e400' is out of the range of a double (+-1.8e308)"},
           {" --size 16384x16384", "--size: 16384x16384 is too large (at most 33554432 pixels in all"},
           {" --size 0x10", "out of range"}}) {
    const CommandResult r = run_app("ef-distance", common + c.args);
    expect_error(r, 2, "ef-distance", c.message);
    EXPECT_FALSE(fs::exists(out)) << c.args << ": the distances were written before the options were checked";
    EXPECT_FALSE(fs::exists(png)) << c.args;
  }
  // The largest picture the message promises is accepted (at parse time; not rendered here).
  expect_error(run_app("ef-path", mesh + " 0 1 --png " + q(png) + " --size 8192x4096 --elevation 100"), 2, "ef-path",
               "--elevation");
  const CommandResult r = run_app("gcs-reconstruct", data_file("vault-sheet.xyz") + " -o " + q(dir_ / "v.ply") +
                                                         " --png " + q(png) + " --size 16384x16384");
  expect_error(r, 2, "gcs-reconstruct", "--size");
  EXPECT_FALSE(fs::exists(dir_ / "v.ply"));
}

TEST_F(AppsCommon, OutputsAreCheckedBeforeAnyWork) {
  // Before, ef-twist and gcs-reconstruct did all their work and then failed to write.
  const std::string cloud = data_file("vault-sheet.xyz");
  expect_error(run_app("gcs-reconstruct", cloud + " -o " + q(dir_ / "out.xyz")), 2, "gcs-reconstruct",
               "unsupported extension '.xyz'");
  expect_error(run_app("gcs-reconstruct", cloud + " -o " + q(dir_ / "missing" / "out.ply")), 2, "gcs-reconstruct",
               "does not exist");
  expect_error(run_app("ef-twist", data_file("neck.off") + " -o " + q(dir_ / "fixed.txt")), 2, "ef-twist",
               "unsupported extension");
  expect_error(run_app("ef-shapes", "torus -o " + q(dir_ / "t.off")), 2, "ef-shapes", "unsupported extension '.off'");
  expect_error(run_app("ef-shapes", "torus --mesh -o " + q(dir_ / "t.xyz")), 2, "ef-shapes", "'.xyz'");
  expect_error(run_app("ef-shapes", "sphere -o " + q(dir_ / "t.xyz")), 2, "ef-shapes", "SHAPE: sphere not in");
  expect_error(run_app("gcs-reconstruct", cloud + " -o " + q(dir_ / "o.ply") + " --snapshots " + q(dir_ / "none")), 2,
               "gcs-reconstruct", "is not a directory");
}

TEST_F(AppsCommon, SeedsAndCountsAreNeverWrappedAround) {
  const std::string out = " -o " + q(dir_ / "s.xyz");
  for (const std::string seed : {"-1", "18446744073709551616", "1.5", "0x10", "nan"}) {
    const CommandResult r = run_app("ef-shapes", "torus --points 10 --seed " + seed + out);
    EXPECT_EQ(r.exit_code, 2) << seed << ": " << r.err;
    EXPECT_NE(r.err.find("--seed"), std::string::npos) << r.err;
  }
  expect_error(run_app("ef-shapes", "torus --points 10 --seed -1" + out), 2, "ef-shapes",
               "--seed: -1 is out of range (0 ... 18446744073709551615)");
  expect_error(run_app("ef-shapes", "torus --points 10 --surface-seed 18446744073709551616" + out), 2, "ef-shapes",
               "--surface-seed: 18446744073709551616 is out of range");
  expect_error(run_app("gcs-eval", data_file("neck.off") + " " + data_file("neck.off") + " --seed -1"), 2, "gcs-eval",
               "--seed: -1 is out of range");
  expect_error(run_app("gcs-reconstruct", data_file("vault-sheet.xyz") + " -o " + q(dir_ / "v.ply") +
                                              " --seed 18446744073709551616"),
               2, "gcs-reconstruct", "--seed");
  expect_error(run_app("ef-twist", data_file("neck.off") + " -o " + q(dir_ / "f.off") + " --max-repairs -1"), 2,
               "ef-twist", "--max-repairs: -1 is out of range");
  expect_error(run_app("ef-shapes", "torus --points -5" + out), 2, "ef-shapes", "--points: -5 is out of range (1 ...");
  // The largest seed is a seed.
  const CommandResult r = run_app("ef-shapes", "torus --points 10 --seed 18446744073709551615" + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(AppsCommon, RangeMessagesAreReadable) {
  // Before: "Value -1 not in range 0.000000 to 179769313486231570814527423731704356798070567525844996..."
  CommandResult r = run_app("ef-twist", data_file("neck.off") + " -o " + q(dir_ / "f.off") + " --radius -1");
  expect_error(r, 2, "ef-twist", "--radius: -1 is out of range (>= 0)");
  EXPECT_EQ(r.err.find("0.000000"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 200u) << r.err;
  r = run_app("gcs-reconstruct", data_file("vault-sheet.xyz") + " -o " + q(dir_ / "v.ply") + " --fit-smoothness nan");
  expect_error(r, 2, "gcs-reconstruct", "--fit-smoothness: nan is not a number (0 ... 1e9)");
  r = run_app("gcs-reconstruct", data_file("vault-sheet.xyz") + " -o " + q(dir_ / "v.ply") + " --fit-smoothness 1e400");
  expect_error(r, 2, "gcs-reconstruct", "'1e400' is out of the range of a double (+-1.8e308)");
  r = run_app("ef-shapes", "torus --radius 0 -o " + q(dir_ / "t.xyz"));
  expect_error(r, 2, "ef-shapes", "--radius: 0 is out of range (> 0)");
  r = run_app("ef-distance", data_file("neck.off") + " --source 0 --max-distance -2");
  expect_error(r, 2, "ef-distance", "--max-distance: -2 is out of range (>= 0)");
  r = run_app("ef-front", data_file("neck.off") + " --source 0 --levels 99999999999");
  expect_error(r, 2, "ef-front", "--levels: 99999999999 is out of range (0 ... 2147483647)");
}

// ---------------------------------------------------------------------------------------------
// Interrupted writes

/// Starts EDGEFRONT_APP_DIR/ef-shapes writing a large point file to `target`; returns its pid.
pid_t start_big_write(const fs::path& target) {
  const std::string app = (fs::path(EDGEFRONT_APP_DIR) / "ef-shapes").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Default actions, whatever the test runner set (an ignored SIGINT would be inherited).
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(app.c_str(), app.c_str(), "torus", "--points", "300000", "-o", target.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

TEST_F(AppsCommon, SignalsDuringAWriteLeaveNoTemporary) {
  for (const int sig : {SIGINT, SIGTERM, SIGKILL}) {
    const fs::path target = dir_ / "big.xyz";
    const pid_t pid = start_big_write(target);
    ASSERT_GT(pid, 0);
    // Wait until the temporary exists: the app is writing.
    bool writing = false;
    for (int i = 0; i < 20000 && !writing; ++i) {
      writing = !temporaries("big.xyz").empty();
      if (!writing) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_TRUE(writing) << "the app did not start writing";
    ASSERT_EQ(::kill(pid, sig), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status << " for signal " << sig;
    EXPECT_FALSE(fs::exists(target)) << sig;
    if (sig == SIGKILL) {
      // Nothing can clean up after SIGKILL: the next write to the same target does.
      EXPECT_EQ(temporaries("big.xyz").size(), 1u);
      const CommandResult r = run_app("ef-shapes", "torus --points 10 -o " + q(target));
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    EXPECT_TRUE(temporaries("big.xyz").empty()) << "signal " << sig << " left " << temporaries("big.xyz").front();
  }
}

}  // namespace
