#include "core/io/vtu.h"

#include <string>

#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::tagged_box;
using io_test::written;

// The whitespace-separated values of the DataArray named `name` in `xml`.
std::vector<std::string> data_array(const std::string& xml, const std::string& name) {
  const std::size_t tag = xml.find("Name=\"" + name + "\"");
  EXPECT_NE(tag, std::string::npos) << name;
  const std::size_t start = xml.find('>', tag) + 1;
  const std::size_t end = xml.find("</DataArray>", start);
  std::vector<std::string> values;
  std::size_t pos = start;
  while (pos < end) {
    const std::size_t first = xml.find_first_not_of(" \n", pos);
    if (first >= end) break;
    const std::size_t last = std::min(xml.find_first_of(" \n", first), end);
    values.push_back(xml.substr(first, last - first));
    pos = last;
  }
  return values;
}

TEST(Vtu, ArraysHoldOneEntryPerPointAndCell) {
  const Mesh mesh = tagged_box();
  const std::string xml = written([&](OutputBuffer& out) { return write_vtu(mesh, out); });
  EXPECT_NE(xml.find("NumberOfPoints=\"8\" NumberOfCells=\"18\""), std::string::npos);
  EXPECT_EQ(data_array(xml, "Points").size(), 8u * 3u);
  EXPECT_EQ(data_array(xml, "connectivity").size(), 12u * 3u + 6u * 4u);
  const std::vector<std::string> offsets = data_array(xml, "offsets");
  ASSERT_EQ(offsets.size(), 18u);
  EXPECT_EQ(offsets.back(), "60");
  const std::vector<std::string> types = data_array(xml, "types");
  ASSERT_EQ(types.size(), 18u);
  EXPECT_EQ(types.front(), "5");
  EXPECT_EQ(types.back(), "10");
  const std::vector<std::string> tags = data_array(xml, "tag");
  ASSERT_EQ(tags.size(), 18u);
  EXPECT_EQ(tags[0], "1");
  EXPECT_EQ(tags[12], "7");
}

}  // namespace
}  // namespace afmesh
