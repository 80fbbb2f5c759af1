// Parameters as given, and the back-end's table that types, bounds and
// defaults them: unknown names and bad values are typed errors naming what
// is valid, on every path (registry, viewport, typed reads).
#include "tsr/med/parameters.hpp"

#include <gtest/gtest.h>

#include "tsr/med/parameter_table.hpp"
#include "tsr/med/viewport_registry.hpp"

using namespace tsr::med;

namespace {

const ParameterTable& table() {
  static const ParameterTable t(
      "test", {integerParameter("spp", 16, 1, 1 << 20, "samples per pixel"),
               positiveParameter("sigmaS", 8.0, 64, "spatial std. dev."), flagParameter("shadows", true, "shadow maps"),
               choiceParameter("filter", "none", {"none", "pixel"}, "filter")});
  return t;
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Parameters, ParseGivesTypedValues) {
  EXPECT_EQ(Parameters::parse("spp=16").second, ParameterValue(std::int64_t{16}));
  EXPECT_EQ(Parameters::parse("t=0.25").second, ParameterValue(0.25));
  EXPECT_EQ(Parameters::parse("shadows=false").second, ParameterValue(false));
  EXPECT_EQ(Parameters::parse("mode=direct").second, ParameterValue(std::string("direct")));
  EXPECT_THROW(Parameters::parse("novalue"), ParameterError);
  EXPECT_THROW(Parameters::parse("=3"), ParameterError);
}

TEST(ParameterTable, ReadsGiveTheDefaultOrTheCheckedValue) {
  Parameters p;
  EXPECT_EQ(table().integer(p, "spp"), 16);
  EXPECT_DOUBLE_EQ(table().real(p, "sigmaS"), 8.0);
  EXPECT_TRUE(table().flag(p, "shadows"));
  EXPECT_EQ(table().choice(p, "filter"), "none");
  p.set("sigmaS", std::int64_t{4});
  EXPECT_DOUBLE_EQ(table().real(p, "sigmaS"), 4.0) << "integers read as reals";
  p.set("spp", std::int64_t{0});
  EXPECT_THROW(table().integer(p, "spp"), BadParameterValue);
  EXPECT_THROW(table().integer(p, "undeclared"), std::logic_error) << "reading an undeclared name is a bug";
}

TEST(ParameterTable, AnUnknownNameIsATypedErrorNamingTheValidOnes) {
  Parameters p;
  p.set("sigmaSS", std::int64_t{4});  // the typo of the issue
  EXPECT_THROW(table().validate(p), UnknownParameter);
  const std::string message = messageOf([&] { table().validate(p); });
  EXPECT_NE(message.find("did you mean sigmaS?"), std::string::npos) << message;
  EXPECT_NE(message.find("spp, sigmaS, shadows, filter"), std::string::npos) << message;
}

TEST(ParameterTable, BadValuesAreTypedErrorsNamingTheRange) {
  EXPECT_THROW(table().validate("spp", std::string("many")), BadParameterValue);
  EXPECT_THROW(table().validate("sigmaS", 0.0), BadParameterValue) << "(0, 64]: zero is out";
  EXPECT_THROW(table().validate("sigmaS", 65.0), BadParameterValue);
  EXPECT_THROW(table().validate("shadows", std::int64_t{1}), BadParameterValue);
  const std::string message = messageOf([] { table().validate("filter", std::string("gauss")); });
  EXPECT_NE(message.find("one of none|pixel"), std::string::npos) << message;
  EXPECT_NO_THROW(table().validate("sigmaS", 64.0));
}

TEST(ParameterTable, DescribeListsEveryParameter) {
  const std::string text = table().describe();
  for (const char* line : {"spp", "integer [1, 1048576]", "sigmaS", "real (0, 64]", "shadows", "filter",
                           "choice none|pixel", "samples per pixel"})
    EXPECT_NE(text.find(line), std::string::npos) << line << " missing from\n" << text;
}

TEST(ParameterTable, ADefaultOutsideItsRangeIsADeclarationBug) {
  EXPECT_THROW(ParameterTable("bad", {integerParameter("spp", 0, 1, 4, "")}), ParameterError);
  EXPECT_THROW(ParameterTable("twice", {flagParameter("a", true, ""), flagParameter("a", false, "")}),
               std::logic_error);
}

namespace {
class Recording final : public Viewport {
 public:
  using Viewport::Viewport;
  tsr::med::SceneAdapter::Update synchronize(const tsr::sg::Replica&) override { return {}; }
  RenderStats render(const tsr::sg::Replica&, const View&, FrameBuffer&, const RenderControl&) override { return {}; }
};
}  // namespace

TEST(ViewportRegistry, RefusesUnknownParametersAndViewportsRefuseThemToo) {
  static const BackendCapabilities capabilities{table(), true};
  ViewportRegistry registry;
  registry.add("test", capabilities, [](ViewportSettings s, ContextPool&) -> std::unique_ptr<Viewport> {
    return std::make_unique<Recording>(std::move(s));
  });
  ContextPool pool;
  ViewportSettings settings;
  settings.backend = "test";
  settings.parameters.set("sigmaSS", 4.0);
  EXPECT_THROW(registry.create(settings, pool), UnknownParameter);
  settings.parameters = {};
  settings.parameters.set("spp", std::int64_t{0});
  EXPECT_THROW(registry.create(settings, pool), BadParameterValue);
  settings.parameters = {};
  auto vp = registry.create(settings, pool);
  EXPECT_TRUE(vp->capabilities().progressive);
  EXPECT_THROW(vp->setParameter("sigmaSS", 4.0), UnknownParameter);
  EXPECT_FALSE(vp->settings().parameters.has("sigmaSS")) << "a refused parameter changes nothing";
  vp->setParameter("sigmaS", 4.0);
  EXPECT_TRUE(vp->settings().parameters.has("sigmaS"));
}

TEST(ViewportRegistry, OptionsForSeveralBackEndsReachThoseThatTakeThem) {
  static const BackendCapabilities a{table(), true};
  static const BackendCapabilities b{ParameterTable("other", {integerParameter("msaa", 1, 1, 4, "")}), false};
  ViewportRegistry registry;
  registry.add("a", a, nullptr);
  registry.add("b", b, nullptr);
  Parameters given;
  given.set("spp", std::int64_t{4});
  given.set("msaa", std::int64_t{4});
  EXPECT_NO_THROW(registry.requireDeclared(given, {"a", "b"}));
  EXPECT_EQ(registry.parametersFor("b", given).all().size(), 1u);
  EXPECT_TRUE(registry.parametersFor("a", given).has("spp"));
  EXPECT_THROW(registry.requireDeclared(given, {"b"}), UnknownParameter);
  given.set("sigmaSS", 1.0);
  EXPECT_THROW(registry.requireDeclared(given, {"a", "b"}), UnknownParameter);
}
