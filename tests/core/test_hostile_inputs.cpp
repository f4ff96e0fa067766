// Hostile measured files and inputs (issue 15): values that overflow a float, angles out of
// range, devices instead of files, text that is not UTF-8, and rho_hh's memory at large n.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>
#include <vector>

#include "bxdf/input_file.h"
#include "bxdf/measured/cornell.h"
#include "bxdf/measured/measured_data.h"
#include "bxdf/measured/merl.h"
#include "bxdf/registry.h"
#include "../scratch_folder.h"

using namespace bxdf;
namespace fs = std::filesystem;

// Counts the bytes this thread allocates through operator new while counting is on.
namespace {
thread_local bool g_counting = false;
thread_local size_t g_allocated = 0;
}  // namespace

void* operator new(size_t n) {
  if (g_counting) g_allocated += n;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }

namespace {

using HostileInputs = bxdf::test_support::ScratchFolderTest;
using bxdf::test_support::error_of;

const char* kCornellHeader =
    "# num wls\n31\n\n# wls\n400 410 420 430 440 450 460 470 480 490 500 510 520 530 540 550 "
    "560 570 580\n590 600 610 620 630 640 650 660 670 680 690 700\n\n# theta i, phi i, theta s, "
    "phi_s, spectral sample values\n";

std::string cornell_row(const std::string& phi_i, const std::string& last_value) {
  std::string row = "0.5 " + phi_i + " 0.5 3.14159";
  for (int i = 0; i < 30; ++i) row += " 0.1";
  return row + " " + last_value + "\n";
}

}  // namespace

TEST_F(HostileInputs, PrintableKeepsUtf8AndEscapesTheRest) {
  EXPECT_EQ(printable("plain é ü 漢"), "plain é ü 漢");
  EXPECT_EQ(printable(std::string("a\xff" "b")), "a\\xffb");
  EXPECT_EQ(printable(std::string("\xc3")), "\\xc3");             // truncated sequence
  EXPECT_EQ(printable(std::string("\xc0\xaf")), "\\xc0\\xaf");   // overlong
  EXPECT_EQ(printable(std::string("\xed\xa0\x80")), "\\xed\\xa0\\x80");  // surrogate
  EXPECT_EQ(printable(std::string("t\tn\n\x7f", 5)), "t\\x09n\\x0a\\x7f");
}

TEST_F(HostileInputs, CornellValuesPastFloatRangeAreRefused) {
  std::string msg = error_of([&] {
    read_cornell(write("big.brdf", kCornellHeader + cornell_row("0", "1e39")));
  });
  EXPECT_NE(msg.find("too large for a float"), std::string::npos) << msg;
  EXPECT_NE(msg.find("700 nm"), std::string::npos) << msg;
  // Each value fits a float but their RGB does not: from 540 nm on, the red weights add up to
  // 1.26.
  std::string row = "0.5 0 0.5 3.14159";
  for (int i = 0; i < 31; ++i) row += i >= 14 ? " 3e38" : " 0";
  msg = error_of([&] { read_cornell(write("sum.brdf", kCornellHeader + row + "\n")); });
  EXPECT_NE(msg.find("RGB is not finite"), std::string::npos) << msg;
}

TEST_F(HostileInputs, CornellPhiOutOfRangeIsRefused) {
  const std::string msg = error_of([&] {
    read_cornell(write("phi.brdf", kCornellHeader + cornell_row("1e30", "0.1")));
  });
  EXPECT_NE(msg.find("phi i"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[-2 pi, 2 pi]"), std::string::npos) << msg;
  EXPECT_NO_THROW(read_cornell(write("ok.brdf", kCornellHeader + cornell_row("-3.14159", "0.1"))));
}

TEST_F(HostileInputs, CornellTokensThatAreNotUtf8AreEscaped) {
  const std::string msg = error_of([&] {
    read_cornell(write("bytes.brdf", kCornellHeader + cornell_row("0", "\xff\xfe")));
  });
  EXPECT_NE(msg.find("'\\xff\\xfe' is not a number"), std::string::npos) << msg;
  EXPECT_EQ(printable(msg), msg);
}

TEST_F(HostileInputs, MerlValuesPastFloatRangeAreRefused) {
  // A small header-only file grown to full size: zeros are valid measurements.
  const std::string p = (dir_ / "big.binary").string();
  {
    std::ofstream out(p, std::ios::binary);
    const int32_t dims[3] = {kMerlThetaH, kMerlThetaD, kMerlPhiD};
    out.write(reinterpret_cast<const char*>(dims), sizeof(dims));
    const double big = 1e42;  // finite as a double, Inf as a float
    out.write(reinterpret_cast<const char*>(&big), sizeof(big));
  }
  fs::resize_file(p, kMerlFileBytes);
  const std::string msg = error_of([&] { read_merl(p); });
  EXPECT_NE(msg.find("too large for a float"), std::string::npos) << msg;
  EXPECT_NE(msg.find("red channel at cell 0"), std::string::npos) << msg;
}

TEST_F(HostileInputs, DevicesAndFoldersAreNotReadAsFiles) {
  // A FIFO with no writer would block an open() for ever: it must be refused before that.
  const std::string fifo = (dir_ / "fifo.brdf").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : {std::string("/dev/zero"), std::string("/dev/null"),
                                 std::string("/tmp"), fifo}) {
    SCOPED_TRACE(path);
    EXPECT_NE(error_of([&] { read_cornell(path); }).find("not a regular file"), std::string::npos);
    EXPECT_NE(error_of([&] { read_merl(path); }).find("not a regular file"), std::string::npos);
    EXPECT_NE(error_of([&] { load_measured_data(path); }).find("not a regular file"),
              std::string::npos);
  }
  const std::string msg = error_of([] { read_input_file(std::string("a\0b", 3), 100, "test file"); });
  EXPECT_NE(msg.find("NUL"), std::string::npos) << msg;
  const std::string big = write("big.txt", std::string(101, 'x'));
  EXPECT_NE(error_of([&] { read_input_file(big, 100, "test file"); }).find("the limit is 100"),
            std::string::npos);
  EXPECT_EQ(read_input_file(big, 101, "test file"), std::string(101, 'x'));
}

TEST_F(HostileInputs, MeasuredPathWithNulIsRefusedAtMake) {
  ParamSet p;
  p.set("path", std::string(BXDF_TEST_DATA_DIR "/measured/acryl_blue.brdf") + '\0' + "x");
  const std::string msg = error_of([&] { make("measured", p); });
  EXPECT_NE(msg.find("NUL"), std::string::npos) << msg;
}

TEST_F(HostileInputs, RhoHhMemoryDoesNotGrowWithTheSampleCount) {
  // rho_hh once kept an n-entry permutation: 8.6 GB at the largest n. 4M samples (~0.1 s)
  // would have taken 16 MB.
  ParamSet p;
  p.set("reflectance", RGBValue{0.5, 0.5, 0.5});
  p.set("sigma", 20.0);
  const BxDFPtr m = make("oren_nayar", p);
  g_allocated = 0;
  g_counting = true;
  const RGB r = m->rho_hh(1 << 22, 7);
  g_counting = false;
  EXPECT_LT(g_allocated, 4096u);
  EXPECT_GT(r.r, 0.3f);
  EXPECT_LT(r.r, 0.51f);
}
