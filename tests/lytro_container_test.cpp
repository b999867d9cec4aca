// Lytro containers: writer/reader round trip, SHA-1 names, damage of every kind gives an error.
#include <gtest/gtest.h>

#include "raw_io/lytro_container.hpp"
#include "test_support.hpp"

namespace lfcam {
namespace {

LytroContainer sample() {
  std::vector<LytroSection> components;
  components.push_back(makeLytroSection(LytroSectionKind::Component, std::string("hello, light field")));
  components.push_back(makeLytroSection(LytroSectionKind::Component, std::string(1000, 'x')));
  const nlohmann::json toc = {{"picture", {{"frameArray", {{{"frame", {{"imageRef", components[0].name}}}}}}}},
                              {"other", components[1].name}};
  return makeLytroContainer(toc, std::move(components));
}

TEST(LytroContainer, Sha1NameOfKnownText) {
  const std::string abc = "abc";
  EXPECT_EQ(sha1Name(std::span(reinterpret_cast<const std::uint8_t*>(abc.data()), abc.size())),
            "sha1-a9993e364706816aba3e25717850c26c9cd0d89d");
}

TEST(LytroContainer, RoundTripKeepsEverySectionAndAlignment) {
  const LytroContainer written = sample();
  const auto bytes = serializeLytroContainer(written);
  EXPECT_EQ(bytes.size() % 16, 0u);
  auto read = parseLytroContainer(bytes, "mem");
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->sections.size(), 4u);
  EXPECT_EQ(read->sections[0].kind, LytroSectionKind::Package);
  EXPECT_EQ(read->sections[1].kind, LytroSectionKind::Metadata);
  for (std::size_t k = 1; k < 4; ++k) {
    EXPECT_EQ(read->sections[k].name, written.sections[k].name);
    EXPECT_EQ(read->sections[k].payload, written.sections[k].payload);
    EXPECT_EQ(read->sections[k].offset % 16, 0u);
  }
  EXPECT_EQ(read->tableOfContents, written.tableOfContents);
  const auto refs = read->references();
  ASSERT_EQ(refs.size(), 2u);
  EXPECT_EQ(refs[0].pointer, "/other");
  EXPECT_EQ(refs[1].pointer, "/picture/frameArray/0/frame/imageRef");
  ASSERT_NE(read->find(refs[1].name), nullptr);
  EXPECT_EQ(read->find(refs[1].name)->payload.size(), 18u);
}

TEST(LytroContainer, SectionsInAnyOrderAndUnknownOnesAreKept) {
  LytroContainer c = sample();
  std::swap(c.sections[2], c.sections[3]);  // components before... any order
  LytroSection unknown;
  unknown.kind = LytroSectionKind::Component;
  unknown.name = "vendor-private-blob";  // not a SHA-1 name: kept unchecked
  unknown.payload = {1, 2, 3};
  c.sections.insert(c.sections.begin() + 1, unknown);
  auto read = parseLytroContainer(serializeLytroContainer(c), "mem");
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->sections.size(), 5u);
  EXPECT_EQ(read->sections[1].name, "vendor-private-blob");
  EXPECT_FALSE(read->tableOfContents.is_null());  // the LFM found wherever it is
}

TEST(LytroContainer, DamageIsAnErrorNeverACrash) {
  const auto good = serializeLytroContainer(sample());
  // Every truncation.
  for (std::size_t n = 0; n < good.size(); ++n) {
    auto r = parseLytroContainer(std::span(good.data(), n), "t.lfp");
    if (n < 8) {
      EXPECT_FALSE(r);
    }
    if (!r) {
      EXPECT_EQ(r.error().message.rfind("t.lfp: ", 0), 0u) << r.error().message;
    }
  }
  // A flipped payload byte: the SHA-1 no longer matches.
  auto bad = good;
  bad[bad.size() - 20] ^= 0x40;
  auto r = parseLytroContainer(bad, "b.lfp");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("SHA-1"), std::string::npos) << r.error().message;
  // A length far beyond the file.
  bad = good;
  bad[16 + 12] = 0x7f;
  r = parseLytroContainer(bad, "l.lfp");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("truncated"), std::string::npos) << r.error().message;
  // Wrong magic.
  bad = good;
  bad[1] = 'X';
  EXPECT_FALSE(parseLytroContainer(bad, "m.lfp"));
  // Every single-byte corruption of the headers is either accepted or an error.
  for (std::size_t k = 0; k < 128; ++k) {
    bad = good;
    bad[k] ^= 0xff;
    (void)parseLytroContainer(bad, "x.lfp");
  }
}

TEST(LytroContainer, WriteAndReadAFile) {
  test::TempDir dir;
  ASSERT_TRUE(writeLytroContainer(dir / "a.lfp", sample()));
  EXPECT_TRUE(looksLikeLytroContainer(dir / "a.lfp"));
  auto read = readLytroContainer(dir / "a.lfp");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->sections.size(), 4u);
  auto missing = readLytroContainer(dir / "none.lfp");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::Io);
}

}  // namespace
}  // namespace lfcam
