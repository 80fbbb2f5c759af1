#pragma once
// The body of every fuzz target: one outside decoder fed arbitrary bytes.
// A body returns normally when the decoder accepts the bytes or refuses
// them with its documented typed error; anything else (another exception,
// a crash, a sanitizer report, a broken round trip) is a finding. The
// libFuzzer entry (fuzz_entry.cpp) and the gcc replay test
// (regression_replay_test.cpp) call these same functions.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace tsr::fuzz {

using Bytes = std::span<const std::uint8_t>;

// A stream of encoded change lists, each decoded and applied to one replica.
void wireCodec(Bytes bytes);
// One framed message: header, then the payload decoded as its type says.
void clusterMessages(Bytes bytes);
// A RenderTile's pixel bytes, with the tile's size, compression and outputs
// taken from the first four bytes.
void pixelCodec(Bytes bytes);
// A .gltf (JSON) or .glb (by its magic) imported from memory.
void gltfImport(Bytes bytes);
// The scene of an import cache entry (parsed_scene_codec), after its header.
void importCache(Bytes bytes);
// A cluster configuration file's text.
void clusterConfig(Bytes bytes);
// tessera-launch's rendezvous: an address file's contents, a node rank's line.
void launchAddressFile(Bytes bytes);
void launchRankLine(Bytes bytes);
// tessera-viewer's --script file and camera bookmarks file.
void viewerScript(Bytes bytes);
void cameraBookmarks(Bytes bytes);
// tessera-anaglyph's --script file.
void anaglyphScript(Bytes bytes);
// tessera-cull: one HTTP request through parsing and routing to its reply;
// one text message of a /v1/preview stream.
void cullHttpRequest(Bytes bytes);
void cullPreviewMessage(Bytes bytes);

struct Target {
  std::string_view name;  // the folder of its corpus and regressions
  void (*run)(Bytes);
};
// Every target this build has (those whose layers are built).
std::vector<Target> allTargets();

}  // namespace tsr::fuzz
