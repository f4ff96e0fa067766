// Hostile material files and output targets (issue 15): deep nesting, numbers past double range,
// bytes that are not UTF-8, duplicate keys, a wrapping version, a measured path that fails, and
// the promises of atomic writes (read-only and symlinked targets, left-overs, long names).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "bxdf/input_file.h"
#include "bxdf/io/atomic_file.h"
#include "bxdf/io/json_text.h"
#include "bxdf/io/material_json.h"
#include "../scratch_folder.h"

using namespace bxdf;
namespace fs = std::filesystem;

namespace {

class HostileFiles : public bxdf::test_support::ScratchFolderTest {
 protected:
  std::string load_error(const std::string& text) {
    const std::string p = write("m.json", text);
    return bxdf::test_support::error_of([&] { io::load_material(p); });
  }
  void write_atomically(const std::string& path, const std::string& text) {
    io::write_file_atomically(path, [&](const std::string& temp) { std::ofstream(temp) << text; });
  }
};

const std::string kGood = R"({"model": "lambertian", "params": {"reflectance": 0.5}})";

}  // namespace

TEST_F(HostileFiles, DeepNestingIsRefusedWithoutRecursion) {
  // 100,000 levels once overflowed the stack while the error message printed the value.
  const std::string msg = load_error(R"({"model": "lambertian", "params": )" +
                                     std::string(100000, '[') + std::string(100000, ']') + "}");
  EXPECT_NE(msg.find("m.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("nesting deeper than 256"), std::string::npos) << msg;
  // Nesting within the limit still reaches the reader, whose message stays one level deep.
  const std::string nested = load_error(R"({"model": "lambertian", "params": {"reflectance": )" +
                                        std::string(200, '[') + std::string(200, ']') + "}}");
  EXPECT_NE(nested.find("params.reflectance"), std::string::npos) << nested;
  EXPECT_NE(nested.find("[[...]]"), std::string::npos) << nested;
  EXPECT_LT(nested.size(), 300u) << nested;
}

TEST_F(HostileFiles, NumberPastDoubleRangeNamesTheFile) {
  const std::string msg = load_error(R"({"model": "lambertian", "params": {"reflectance": 1e999}})");
  EXPECT_NE(msg.find("m.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("number overflow"), std::string::npos) << msg;
}

TEST_F(HostileFiles, BytesThatAreNotUtf8AreEscapedInMessages) {
  const std::string msg = load_error("{\"model\": \"lamb\xff\xfe\"}");
  EXPECT_NE(msg.find("not valid JSON"), std::string::npos) << msg;
  EXPECT_NE(msg.find("\\xff"), std::string::npos) << msg;
  EXPECT_EQ(printable(msg), msg);  // valid UTF-8, no control characters
  // The file name too.
  const std::string bad_name = write("m\xff.json", "{");
  try {
    io::load_material(bad_name);
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("m\\xff.json"), std::string::npos) << e.what();
  }
}

TEST_F(HostileFiles, DuplicateKeysAreRefused) {
  std::string msg = load_error(R"({"model": "lambertian", "model": "oren_nayar"})");
  EXPECT_NE(msg.find("duplicate key \"model\""), std::string::npos) << msg;
  msg = load_error(R"({"model": "lambertian", "params": {"reflectance": 0.1, "reflectance": 0.9}})");
  EXPECT_NE(msg.find("duplicate key \"reflectance\""), std::string::npos) << msg;
  // The same key in sibling objects is fine.
  EXPECT_NO_THROW(io::parse_json(R"([{"a": 1}, {"a": 2}, {"b": {"a": 3}, "a": 4}])", "x"));
}

TEST_F(HostileFiles, VersionIsComparedAsA64BitNumber) {
  for (const char* v : {"4294967297", "18446744073709551615", "-4294967295", "0", "2"}) {
    SCOPED_TRACE(v);
    const std::string msg =
        load_error(std::string(R"({"format": "bxdf-material", "version": )") + v +
                   R"(, "model": "lambertian"})");
    EXPECT_NE(msg.find("field 'version'"), std::string::npos) << msg;
  }
  EXPECT_EQ(load_error(R"({"format": "bxdf-material", "version": 1, "model": "lambertian"})"), "");
}

TEST_F(HostileFiles, BadMeasuredPathNamesTheMaterialFile) {
  const std::string msg = load_error(R"({"model": "measured", "params": {"path": "/nonexistent/x.brdf"}})");
  EXPECT_EQ(msg.rfind((dir_ / "m.json").string(), 0), 0u) << msg;
  EXPECT_NE(msg.find("/nonexistent/x.brdf"), std::string::npos) << msg;
}

TEST_F(HostileFiles, MaterialFileMustBeARegularFile) {
  for (const char* path : {"/dev/zero", "/tmp"}) {
    try {
      io::load_material(path);
      FAIL() << path;
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
  }
}

TEST_F(HostileFiles, ReadOnlyTargetIsRefusedAndKept) {
  const std::string target = write("out.json", "old");
  fs::permissions(target, fs::perms::owner_read | fs::perms::group_read);
  EXPECT_THROW(write_atomically(target, "new"), ParameterError);
  EXPECT_EQ(read(target), "old");
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::group_read);
}

TEST_F(HostileFiles, ReplacedFileKeepsItsMode) {
  const std::string target = write("out.json", "old");
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write);
  write_atomically(target, "new");
  EXPECT_EQ(read(target), "new");
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
}

TEST_F(HostileFiles, SymlinkTargetIsWrittenThrough) {
  fs::create_directories(dir_ / "real");
  const std::string real = write("real/out.json", "old");
  const fs::path link = dir_ / "link.json";
  fs::create_symlink("real/out.json", link);
  write_atomically(link.string(), "new");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read(real), "new");
  // A dangling link creates the file it names.
  const fs::path dangling = dir_ / "dangling.json";
  fs::create_symlink("real/created.json", dangling);
  write_atomically(dangling.string(), "made");
  EXPECT_TRUE(fs::is_symlink(dangling));
  EXPECT_EQ(read((dir_ / "real/created.json").string()), "made");
}

TEST_F(HostileFiles, StaleTemporariesOfDeadProcessesAreRemoved) {
  const std::string target = (dir_ / "out.exr").string();
  // The temporary name a killed process would have left (pid 2^22 + 1 is past pid_max's default
  // and cannot be running), and one of a live process (ours is skipped; use pid 1).
  const std::string stale = (dir_ / "out.exr.partial-4194305-0.exr").string();
  const std::string live = (dir_ / "out.exr.partial-1-0.exr").string();
  std::ofstream(stale) << "half";
  std::ofstream(live) << "busy";
  const std::string name = fs::path(io::temporary_sibling(target)).filename().string();
  EXPECT_EQ(name.rfind("out.exr.partial-" + std::to_string(::getpid()) + "-", 0), 0u) << name;
  write_atomically(target, "new");
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_EQ(read(target), "new");
}

TEST_F(HostileFiles, LongNamesFitWithTheTemporarySuffix) {
  const std::string name = std::string(244 - 5, 'n') + ".json";  // 244 bytes: a valid name
  ASSERT_EQ(name.size(), 244u);
  const std::string target = (dir_ / name).string();
  write_atomically(target, "long");
  EXPECT_EQ(read(target), "long");
  EXPECT_LE(fs::path(io::temporary_sibling(target)).filename().string().size(), 255u);
  EXPECT_EQ(fs::path(io::temporary_sibling(target)).extension(), ".json");
}

TEST_F(HostileFiles, FailedWriteLeavesTheOldFileAndNoTemporary) {
  const std::string target = write("out.json", "old");
  EXPECT_THROW(io::write_file_atomically(target, [](const std::string& temp) {
                 std::ofstream(temp) << "partial";
                 throw std::runtime_error("disk full");
               }),
               std::runtime_error);
  EXPECT_EQ(read(target), "old");
  EXPECT_EQ(files_in_folder(), 1u);
}
