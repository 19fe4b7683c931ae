// InputProtection: an output is refused when it is an input, by file identity (a symlink, a
// hard link, another spelling), in whichever order the two are met; two outputs that are one file
// are refused; without the guard nothing is recorded.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdlib.h>

#include "vstcal/core/error.h"
#include "vstcal/files/input_protection.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

namespace fs = std::filesystem;

class InputProtectionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "vstcal-protect-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
    std::ofstream(dir_ / "in.json") << "{}";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(InputProtectionTest, OutputReadBeforeOrAfterIsRefused) {
  {
    const InputProtection guard;
    ReadInputFile(dir_ / "in.json", "a JSON file");
    EXPECT_THROW(CheckOutputs({dir_ / "." / "in.json"}), InputError);
    EXPECT_THROW(WriteFileAtomically(dir_ / "in.json", "x"), InputError);
    EXPECT_NO_THROW(CheckOutputs({dir_ / "out.json"}));
  }
  {
    const InputProtection guard;
    DeclareOutputs({dir_ / "in.json"});
    try {
      ReadInputFile(dir_ / "in.json", "a JSON file");
      FAIL();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("is the input"), std::string::npos) << e.what();
    }
  }
  std::ifstream in(dir_ / "in.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "{}");
}

TEST_F(InputProtectionTest, LinksAreTheSameFile) {
  fs::create_symlink(dir_ / "in.json", dir_ / "sym.json");
  fs::create_hard_link(dir_ / "in.json", dir_ / "hard.json");
  const InputProtection guard;
  ReadInputFile(dir_ / "in.json", "a JSON file");
  EXPECT_THROW(CheckOutputs({dir_ / "sym.json"}), InputError);
  EXPECT_THROW(CheckOutputs({dir_ / "hard.json"}), InputError);
}

TEST_F(InputProtectionTest, TwoOutputsThatAreOneFile) {
  EXPECT_THROW(CheckOutputs({dir_ / "a.json", dir_ / "sub" / ".." / "a.json"}), InputError);
  fs::create_hard_link(dir_ / "in.json", dir_ / "hard.json");
  EXPECT_THROW(CheckOutputs({dir_ / "in.json", dir_ / "hard.json"}), InputError);
  EXPECT_NO_THROW(CheckOutputs({dir_ / "a.json", dir_ / "b.json", ""}));
}

TEST_F(InputProtectionTest, WithoutAGuardNothingIsRecorded) {
  ReadInputFile(dir_ / "in.json", "a JSON file");
  EXPECT_NO_THROW(WriteFileAtomically(dir_ / "in.json", "{\"a\": 1}"));
  const InputProtection guard;  // a new run starts with no inputs
  EXPECT_NO_THROW(CheckOutputs({dir_ / "in.json"}));
}

}  // namespace
}  // namespace vstcal
