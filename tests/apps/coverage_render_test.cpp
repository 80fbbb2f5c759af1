// tessera-render --backend coverage as a user runs it: a JSON ranking that
// accounts for every pixel, the false-colour image, one-line errors.
#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "tsr/med/image_file.hpp"

namespace {

using tsr::test::Outcome;

class CoverageCommand : public tsr::test::CommandTest {
 protected:
  Outcome run(const std::string& args) { return runBinary(TSR_RENDER_PATH, args); }
};

TEST_F(CoverageCommand, JsonRankingAccountsForEveryPixel) {
  const Outcome r = run("builtin:cornell --backend coverage --size 96x64 --output rank.json --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = nlohmann::json::parse(slurp(dir / "rank.json"));
  EXPECT_EQ(j["width"], 96);
  EXPECT_EQ(j["height"], 64);
  const auto& objects = j["objects"];
  ASSERT_GE(objects.size(), 4u);
  std::uint64_t sum = j["background"].get<std::uint64_t>();
  double fractions = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    sum += objects[i]["pixels"].get<std::uint64_t>();
    fractions += objects[i]["fraction"].get<double>();
    EXPECT_TRUE(objects[i]["id"].is_number_unsigned());
    EXPECT_TRUE(objects[i]["name"].is_string());
    if (i) {
      EXPECT_GE(objects[i - 1]["pixels"].get<std::uint64_t>(), objects[i]["pixels"].get<std::uint64_t>());
    }
  }
  EXPECT_EQ(sum, 96u * 64u);
  EXPECT_NEAR(fractions + j["background"].get<double>() / (96 * 64), 1.0, 1e-9);
  EXPECT_EQ(objects[0]["name"], "white");
}

TEST_F(CoverageCommand, PngIsTheFalseColourIdImage) {
  ASSERT_EQ(run("builtin:cornell --backend coverage --size 48x40 --output ids.png --quiet").status, 0);
  ASSERT_EQ(run("builtin:cornell --backend coverage --size 48x40 --output rank.json --quiet").status, 0);
  auto image = tsr::med::readImage((dir / "ids.png").string());
  ASSERT_EQ(image.width, 48u);
  ASSERT_EQ(image.height, 40u);
  // False colours are never black, the background always is.
  std::uint64_t lit = 0;
  for (const auto& p : image.colour) lit += p.r + p.g + p.b > 0.0f;
  auto j = nlohmann::json::parse(slurp(dir / "rank.json"));
  EXPECT_EQ(lit, 48u * 40u - j["background"].get<std::uint64_t>());
}

TEST_F(CoverageCommand, BadInputIsOneErrorLine) {
  expectOneErrorLine(run("builtin:cornell --backend coverage --size 0x8 --output r.json"), "--size");
  expectOneErrorLine(run("builtin:cornell --size 8x8 --spp 1 --output r.json"), "--backend coverage");
  expectOneErrorLine(run("builtin:cornell --backend coverage --size 8x8 --output nosuchdir/r.json"), "cannot write");
  expectOneErrorLine(run("builtin:cornell --backend coverage --size 8x8 --param threads=-1 --output r.json"),
                     "threads");
  expectOneErrorLine(run("missing.gltf --backend coverage --size 8x8 --output r.json"), "missing.gltf");
}

}  // namespace
