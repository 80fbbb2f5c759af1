// The converted-scene cache (ImportOptions::cacheDir): stored on the first
// import, read back on the second with the same result, converted again
// when the file changes, and refused and rebuilt when the entry is damaged,
// truncated or invalid, which never fails the import.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "builtin/builtin_scenes.hpp"
#include "cache/parsed_scene_codec.hpp"
#include "cache/scene_cache.hpp"
#include "cache/stamp_index.hpp"
#include "test_scenes.hpp"
#include "tsr/sg/geometry.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::test {
namespace {

namespace fs = std::filesystem;

struct Cached {
  TempDir dir;
  sg::ImportOptions options;
  std::string file = dir.file("scene.glb");
  Cached() {
    options.cacheDir = dir.file("cache");
    tinyScene().writeGlb(file);
  }
  // Imports into a fresh scene; the cache note and the first geometry's positions.
  std::pair<std::string, std::vector<sg::Vec3>> import() const {
    sg::Scene scene;
    const sg::ImportResult r = sg::importScene(scene, file, options);
    for (auto id : scene.ids())
      if (const auto* g = scene.find<sg::Geometry>(id)) return {r.cache, g->positions().toVector()};
    return {r.cache, {}};
  }
  fs::path entry() const {
    for (const auto& e : fs::directory_iterator(options.cacheDir)) return e.path();
    return {};
  }
};

TEST(SceneCache, StoredThenReadBackTheSame) {
  Cached c;
  const auto first = c.import();
  EXPECT_EQ(first.first, "stored");
  const auto second = c.import();
  EXPECT_EQ(second.first, "hit");
  EXPECT_EQ(second.second, first.second);
  EXPECT_EQ(second.second.size(), 3u);
}

// A hit's meshes are the mapped entry's bytes, not copies; an edit copies
// the edited array first, so the entry (and every other scene that mapped
// it) never changes.
TEST(SceneCache, AHitUsesTheEntrysArraysInPlaceAndCopiesThemBeforeAnEdit) {
  Cached c;
  c.import();
  const std::vector<std::uint8_t> entryBefore = readBytes(c.entry().string());
  sg::Scene scene;
  ASSERT_EQ(sg::importScene(scene, c.file, c.options).cache, "hit");
  sg::Geometry* g = nullptr;
  for (auto id : scene.ids())
    if (auto* found = scene.find<sg::Geometry>(id)) g = found;
  ASSERT_NE(g, nullptr);
  EXPECT_FALSE(g->positions().owned()) << "the positions were copied out of the entry";
  EXPECT_FALSE(g->indices().owned());
  const sg::Vec3 first = g->positions()[0], second = g->positions()[1];
  ASSERT_NE(first, sg::Vec3(0.5f));
  g->updatePositions(0, std::vector<sg::Vec3>{sg::Vec3(0.5f)});
  EXPECT_TRUE(g->positions().owned()) << "edited in the mapped entry";
  EXPECT_EQ(g->positions()[0], sg::Vec3(0.5f));
  EXPECT_EQ(g->positions()[1], second);
  EXPECT_EQ(readBytes(c.entry().string()), entryBefore);
  EXPECT_EQ(c.import().second[0], first) << "another scene from the same entry saw the edit";
}

// An entry others may rewrite is validated and copied: its pages could
// change under the scene after the check.
TEST(SceneCache, AnEntryOthersCanWriteIsCopiedOut) {
  Cached c;
  c.import();
  fs::permissions(c.entry(), fs::perms::group_write, fs::perm_options::add);
  sg::Scene scene;
  ASSERT_EQ(sg::importScene(scene, c.file, c.options).cache, "hit");
  for (auto id : scene.ids()) {
    if (const auto* g = scene.find<sg::Geometry>(id)) {
      EXPECT_TRUE(g->positions().owned());
    }
  }
}

// Arrays are aligned in the payload, so in place they are read as elements.
TEST(SceneCache, DecodedInPlaceEqualsDecodedByCopy) {
  Cached c;
  c.import();
  std::vector<std::uint8_t> payload = readBytes(c.entry().string());
  payload.erase(payload.begin(), payload.begin() + sg::cache::kHeaderBytes);
  const auto keeper = std::make_shared<const std::vector<std::uint8_t>>(payload);
  const sg::parsed::Scene copied = sg::parsed::decodeScene(payload);
  const sg::parsed::Scene held = sg::parsed::decodeScene(*keeper, keeper);
  ASSERT_EQ(held.primitives.size(), copied.primitives.size());
  ASSERT_TRUE(held.primitives[0].held.has_value());
  EXPECT_FALSE(copied.primitives[0].held.has_value());
  const auto at = reinterpret_cast<const std::uint8_t*>(held.primitives[0].arrays().positions.data());
  EXPECT_TRUE(at >= keeper->data() && at < keeper->data() + keeper->size()) << "not in the payload";
  EXPECT_EQ(sg::parsed::encodeScene(held), payload);
  EXPECT_EQ(sg::parsed::encodeScene(copied), payload);
}

// The fuzz target's seeds are payloads of today's format: after a format
// change, `make_fuzz_corpus` (and the hand-made seeds' recipe in
// docs/fuzzing-and-sanitizers.md) must make them again, or the fuzzer only
// ever sees refusals.
TEST(SceneCache, FuzzSeedsAreEntriesOfTodaysFormat) {
  int seeds = 0;
  for (const auto& e : fs::directory_iterator(TSR_IMPORT_CACHE_SEEDS)) {
    SCOPED_TRACE(e.path().string());
    const std::vector<std::uint8_t> seed = readBytes(e.path().string());
    EXPECT_NO_THROW(EXPECT_EQ(sg::parsed::encodeScene(sg::parsed::decodeScene(seed)), seed));
    ++seeds;
  }
  EXPECT_GE(seeds, 4);
}

// A built-in scene is kept under its name; another name (another budget)
// is another entry. The entry is the same bytes as the scene encoded whole
// (the store streams the encoding to the file).
TEST(SceneCache, ABuiltInSceneIsKeptUnderItsName) {
  TempDir dir;
  sg::ImportOptions options;
  options.cacheDir = dir.file("cache");
  const auto import = [&](const std::string& source) {
    sg::Scene scene;
    return sg::importScene(scene, source, options);
  };
  const sg::ImportResult first = import("builtin:plant:20000");
  EXPECT_EQ(first.cache, "stored");
  const sg::ImportResult second = import("builtin:plant:020000");  // the same scene, the same entry
  EXPECT_EQ(second.cache, "hit");
  EXPECT_EQ(second.counts.uniqueTriangles, first.counts.uniqueTriangles);
  EXPECT_EQ(import("builtin:plant:30000").cache, "stored");
  EXPECT_EQ(import("builtin:cornell").cache, "stored");
  // The Cornell box's unit (millimetres) survives the cache.
  const sg::ImportResult cornell = import("builtin:cornell");
  EXPECT_EQ(cornell.cache, "hit");
  EXPECT_FLOAT_EQ(cornell.metresPerUnit, 0.001f);

  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(options.cacheDir)) ++entries;
  EXPECT_EQ(entries, 3u);
  const fs::path entry = sg::cache::entryPath(options.cacheDir, sg::cache::builtinKey("builtin:cornell"));
  const std::vector<std::uint8_t> bytes = readBytes(entry.string());
  const std::vector<std::uint8_t> whole = sg::parsed::encodeScene(sg::builtin::cornell());
  ASSERT_EQ(bytes.size(), sg::cache::kHeaderBytes + whole.size());
  EXPECT_TRUE(std::equal(whole.begin(), whole.end(), bytes.begin() + sg::cache::kHeaderBytes));
}

// A cache folder that cannot be made (a file stands where it should be):
// the import succeeds, the scene is not kept, and no temporary file stays.
TEST(SceneCache, AnEntryThatCannotBeWrittenLeavesTheImportWhole) {
  Cached c;
  writeBytes(c.dir.file("blocked"), {1});
  c.options.cacheDir = c.dir.file("blocked") + "/cache";
  const auto first = c.import();
  EXPECT_NE(first.first.find("not stored (cannot write"), std::string::npos) << first.first;
  EXPECT_EQ(first.second.size(), 3u);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(c.dir.path())) ++files;
  EXPECT_EQ(files, 2u) << "the scene and the blocking file, nothing else";
}

// A file last modified long enough ago is found again by its stamp (its
// bytes are not hashed); a new modification time makes it hashed again.
// A file modified just now gets no stamp recorded.
TEST(SceneCache, AnUnchangedFileIsFoundByItsStamp) {
  Cached c;
  const auto stamps = [&] {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(c.options.cacheDir)) n += e.path().extension() == ".tsrstamp";
    return n;
  };
  EXPECT_EQ(c.import().first, "stored");
  EXPECT_EQ(stamps(), 0u) << "modified too recently to be known by its stamp";
  fs::last_write_time(c.file, fs::file_time_type::clock::now() - std::chrono::hours(1));
  EXPECT_EQ(c.import().first, "hit");
  ASSERT_EQ(stamps(), 1u);
  // Known by the stamp alone: a same-sized file of other bytes with the
  // recorded stamp's time would be taken for the old one, which is why a
  // stamp is only recorded for files that settled before they were hashed.
  const auto recorded = sg::cache::FileStamp::of(c.file);
  ASSERT_TRUE(recorded);
  const auto key = sg::cache::recordedKey(c.options.cacheDir, c.file, c.options, *recorded);
  ASSERT_TRUE(key);
  EXPECT_EQ(*key, sg::cache::key(readBytes(c.file), c.options));
  EXPECT_EQ(c.import().first, "hit");

  GltfBuilder b = tinyScene();
  b.doc["nodes"][0]["name"] = "renamed";
  b.writeGlb(c.file);
  fs::last_write_time(c.file, fs::file_time_type::clock::now() - std::chrono::minutes(30));
  EXPECT_FALSE(sg::cache::recordedKey(c.options.cacheDir, c.file, c.options, *sg::cache::FileStamp::of(c.file)));
  EXPECT_EQ(c.import().first, "stored");
  const auto renamed = sg::cache::recordedKey(c.options.cacheDir, c.file, c.options, *sg::cache::FileStamp::of(c.file));
  ASSERT_TRUE(renamed);
  EXPECT_NE(*renamed, *key);
}

TEST(SceneCache, ChangedFileIsConvertedAgain) {
  Cached c;
  c.import();
  GltfBuilder b = tinyScene();
  b.doc["nodes"][0]["name"] = "renamed";  // other bytes, another key
  b.writeGlb(c.file);
  EXPECT_EQ(c.import().first, "stored");
  EXPECT_EQ(c.import().first, "hit");
}

TEST(SceneCache, DamagedOrTruncatedEntryIsRefusedAndRebuilt) {
  Cached c;
  const auto first = c.import();
  std::vector<std::uint8_t> bytes = readBytes(c.entry().string());
  bytes[bytes.size() - 5] ^= 0x40;
  writeBytes(c.entry().string(), bytes);
  const auto damaged = c.import();
  EXPECT_NE(damaged.first.find("rebuilt (the entry is damaged"), std::string::npos) << damaged.first;
  EXPECT_EQ(damaged.second, first.second);
  EXPECT_EQ(c.import().first, "hit");

  bytes = readBytes(c.entry().string());
  bytes.resize(bytes.size() / 2);
  writeBytes(c.entry().string(), bytes);
  EXPECT_NE(c.import().first.find("rebuilt (the entry is truncated"), std::string::npos);
  writeBytes(c.entry().string(), {1, 2, 3});
  EXPECT_NE(c.import().first.find("rebuilt (the entry is shorter than its header"), std::string::npos);
  EXPECT_EQ(c.import().first, "hit");
  // Entries and sources are mapped, not read: an empty one maps nothing.
  writeBytes(c.entry().string(), {});
  EXPECT_NE(c.import().first.find("rebuilt (the entry is shorter than its header"), std::string::npos);
  EXPECT_EQ(c.import().first, "hit");
}

TEST(SceneCache, AnEmptySourceIsRefusedByName) {
  Cached c;
  writeBytes(c.file, {});
  sg::Scene scene;
  try {
    sg::importScene(scene, c.file, c.options);
    FAIL() << "an empty file imported";
  } catch (const sg::ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.glb"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(scene.ids().empty());
}

// An entry whose header and hash are right but whose scene is not: validated like any input.
TEST(SceneCache, EntryWithAnInvalidSceneIsRefused) {
  Cached c;
  c.import();
  const fs::path entry = c.entry();
  const std::string key = entry.stem().string();
  sg::parsed::Scene bad;
  sg::parsed::Primitive p;
  p.positions = {sg::Vec3(0), sg::Vec3(1, 0, 0), sg::Vec3(0, 1, 0)};
  p.indices = {0, 1, 7};
  bad.primitives.push_back(p);
  std::string why;
  ASSERT_TRUE(sg::cache::store(entry, key, bad, why)) << why;
  const auto r = c.import();
  EXPECT_NE(r.first.find("rebuilt (the entry is invalid: primitive 0 has an index out of range"), std::string::npos)
      << r.first;
  EXPECT_EQ(r.second.size(), 3u);
}

TEST(SceneCache, DecoderRefusesEveryTruncation) {
  Cached c;
  c.import();
  std::vector<std::uint8_t> payload = readBytes(c.entry().string());
  payload.erase(payload.begin(), payload.begin() + sg::cache::kHeaderBytes);
  EXPECT_NO_THROW(sg::parsed::decodeScene(payload));
  for (std::size_t n = 0; n < payload.size(); ++n)
    EXPECT_THROW(sg::parsed::decodeScene(std::span(payload).first(n)), std::runtime_error) << n;
}

TEST(SceneCache, FilesNamingExternalResourcesAreNotStored) {
  Cached c;
  richScene(c.dir).writeGltf(c.file = c.dir.file("rich.gltf"));
  EXPECT_EQ(c.import().first, "not stored (the file names external buffers or images)");
}

}  // namespace
}  // namespace tsr::test

namespace tsr::test {
namespace {

// Volumes survive the cache: a material's medium and the scene's fog read
// back from an entry equal those converted from the file.
TEST(SceneCache, VolumesAndFogSurviveTheCache) {
  TempDir dir;
  GltfBuilder b = tinyScene();
  nlohmann::json material;
  material["extensions"]["TSR_materials_volume"] = {{"scattering", {1.0, 2.0, 3.0}}, {"phaseG", 0.25}};
  b.doc["materials"] = nlohmann::json::array({material});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["scenes"][0]["extensions"]["TSR_scene_medium"] = {{"absorption", {0.5, 0.5, 0.5}}};
  b.doc["extensionsUsed"] = {"TSR_materials_volume", "TSR_scene_medium"};
  b.writeGlb(dir.file("fog.glb"));
  sg::ImportOptions options;
  options.cacheDir = dir.file("cache");
  sg::Scene converted, cached;
  EXPECT_EQ(sg::importScene(converted, dir.file("fog.glb"), options).cache, "stored");
  EXPECT_EQ(sg::importScene(cached, dir.file("fog.glb"), options).cache, "hit");
  EXPECT_EQ(cached.contentHash(), converted.contentHash());
  EXPECT_EQ(cached.count(sg::ContainerType::VolumeMaterial), 2u) << "the sphere's medium and the fog";
}

}  // namespace
}  // namespace tsr::test
