// Protects the loader of optional modules (io/files/optional_module.hpp): the image module is
// found from the build tree, a missing module or entry point is one line naming it and where it
// was looked for, and OWSIM_MODULE_DIR replaces the search.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "geometry/error.hpp"
#include "io/files/optional_module.hpp"
#include "io/images/png_image.hpp"

namespace owsim {
namespace {

std::string module_error_of(auto&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(OptionalModule, ThePngModuleIsFoundBesideTheBuild) {
  const OptionalModule& module = OptionalModule::get("png", "this test");
  EXPECT_NE(module.path().find("lib/owsim/libowsim_png.so"), std::string::npos) << module.path();
  EXPECT_NE(module.symbol("owsim_png_encode"), nullptr);
  EXPECT_EQ(&OptionalModule::get("png", "this test"), &module);  // loaded once
  // A 2 × 1 image encodes to a PNG: the signature, then the IHDR chunk with the size.
  RgbImage image(2, 1);
  const std::vector<unsigned char> png = encode_png(image);
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(std::string(png.begin() + 1, png.begin() + 4), "PNG");
  EXPECT_EQ(png[19], 2);  // width, big-endian
  EXPECT_EQ(png[23], 1);  // height
}

TEST(OptionalModule, AMissingModuleNamesItselfWhatNeedsItAndWhereItLooked) {
  const std::string message =
      module_error_of([] { static_cast<void>(OptionalModule::get("absent", "the frobnicator")); });
  EXPECT_NE(message.find("the frobnicator need the optional module libowsim_absent.so"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("lib/owsim"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(OptionalModule, AMissingEntryPointIsAnError) {
  const OptionalModule& module = OptionalModule::get("png", "this test");
  const std::string message = module_error_of([&] { static_cast<void>(module.symbol("no_such")); });
  EXPECT_NE(message.find("no_such"), std::string::npos) << message;
}

TEST(OptionalModule, TheEnvironmentNamesTheOnlyFolder) {
  ASSERT_EQ(::setenv("OWSIM_MODULE_DIR", "/nonexistent/modules", 1), 0);
  const std::string message =
      module_error_of([] { static_cast<void>(OptionalModule::get("other", "a test")); });
  ::unsetenv("OWSIM_MODULE_DIR");
  EXPECT_NE(message.find("looked in /nonexistent/modules;"), std::string::npos) << message;
}

TEST(OptionalModule, AMissingModuleNamesThePackagesThatBringIt) {
  ASSERT_EQ(::setenv("OWSIM_MODULE_DIR", "/nonexistent/modules", 1), 0);
  const std::string message =
      module_error_of([] { static_cast<void>(OptionalModule::get("gdal", "DEM terrain (terrain.dem)")); });
  ::unsetenv("OWSIM_MODULE_DIR");
  // to build it, and to run the packaged one
  EXPECT_NE(message.find("when libgdal-dev is installed (scripts/setup.sh gdal"), std::string::npos)
      << message;
  EXPECT_NE(message.find("apt install libgdal32"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace owsim
