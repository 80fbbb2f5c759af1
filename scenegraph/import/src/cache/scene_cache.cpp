#include "cache/scene_cache.hpp"

#include <unistd.h>
#include <xxhash.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "cache/parsed_scene_codec.hpp"
#include "files/mapped_file.hpp"

namespace tsr::sg::cache {
namespace {

namespace fs = std::filesystem;
constexpr char kMagic[8] = {'T', 'S', 'R', 'S', 'C', 'E', 'N', 'E'};
// 2: arrays 8-byte aligned in the payload (used in place), XXH3 checksums.
// 3: the scene unit (metresPerUnit) after the rest.
constexpr std::uint32_t kFormat = 3;

// XXH3's 128 bits: not cryptographic, but accidental collisions are
// negligible, and a matching entry is still validated like any outside input.
std::string hex(const XXH128_hash_t& h) {
  char out[33];
  std::snprintf(out, sizeof out, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                static_cast<unsigned long long>(h.low64));
  return out;
}

std::string hashOf(std::span<const std::uint8_t> bytes) { return hex(XXH3_128bits(bytes.data(), bytes.size())); }

struct Header {
  char magic[8];
  std::uint32_t format;
  std::uint32_t importerVersion;
  char key[64];
  std::uint64_t payloadBytes;
  char payloadHash[32];
};
static_assert(sizeof(Header) == kHeaderBytes);
static_assert(kHeaderBytes % 8 == 0, "the payload's arrays are aligned within a page-aligned mapping");

}  // namespace

std::string key(std::span<const std::uint8_t> source, const ImportOptions& o) {
  constexpr std::uint64_t kFile = 0;
  const std::uint64_t settings[] = {kImporterVersion, kFile,           o.smoothNormals,
                                    o.maxFileBytes,   o.maxJsonValues, o.maxAccessorElements,
                                    o.maxImagePixels};
  return hashOf(source) + hashOf({reinterpret_cast<const std::uint8_t*>(settings), sizeof settings});
}

std::string builtinKey(const std::string& canonicalName) {
  constexpr std::uint64_t kBuiltin = 1;
  const std::uint64_t settings[] = {kImporterVersion, kBuiltin};
  return hashOf({reinterpret_cast<const std::uint8_t*>(canonicalName.data()), canonicalName.size()}) +
         hashOf({reinterpret_cast<const std::uint8_t*>(settings), sizeof settings});
}

fs::path entryPath(const fs::path& dir, const std::string& key) { return dir / (key + ".tsrscene"); }

std::optional<parsed::Scene> load(const fs::path& entry, const std::string& key, std::string& why) {
  std::error_code ec;
  if (!fs::is_regular_file(entry, ec)) {
    why = "no entry";
    return std::nullopt;
  }
  // Mapped: the payload is decoded from the page cache, not from a copy, and
  // the meshes' arrays stay there, held by the scene built from them, when
  // the entry is stable (MappedFile::stable: only this user can change what
  // was validated); else they are copied out.
  std::shared_ptr<const MappedFile> file;
  try {
    file = std::make_shared<const MappedFile>(entry);
  } catch (const std::system_error& e) {
    why = std::string("the entry cannot be read: ") + e.what();
    return std::nullopt;
  }
  const std::span<const std::uint8_t> bytes = file->bytes();
  const std::uint64_t size = bytes.size();
  if (size < sizeof(Header)) {
    why = "the entry is shorter than its header";
    return std::nullopt;
  }
  Header h;
  std::memcpy(&h, bytes.data(), sizeof h);
  if (std::memcmp(h.magic, kMagic, 8) != 0 || h.format != kFormat) {
    why = "not a converted scene of this format";
    return std::nullopt;
  }
  if (h.importerVersion != kImporterVersion) {
    why = "made by importer version " + std::to_string(h.importerVersion);
    return std::nullopt;
  }
  if (key.size() != sizeof h.key || std::memcmp(h.key, key.data(), sizeof h.key) != 0) {
    why = "the entry is for another file";
    return std::nullopt;
  }
  if (h.payloadBytes != size - sizeof(Header)) {
    why = "the entry is truncated or too long";
    return std::nullopt;
  }
  const std::span<const std::uint8_t> payload = bytes.subspan(sizeof(Header));
  if (std::memcmp(h.payloadHash, hashOf(payload).data(), sizeof h.payloadHash) != 0) {
    why = "the entry is damaged (its hash does not match)";
    return std::nullopt;
  }
  try {
    return parsed::decodeScene(payload, file->stable() ? file : nullptr);
  } catch (const std::exception& e) {
    why = std::string("the entry is invalid: ") + e.what();
    return std::nullopt;
  }
}

bool store(const fs::path& entry, const std::string& key, const parsed::Scene& scene, std::string& why) {
  Header h{};
  std::memcpy(h.magic, kMagic, 8);
  h.format = kFormat;
  h.importerVersion = kImporterVersion;
  if (key.size() != sizeof h.key) throw std::logic_error("cache keys are 64 characters");
  std::memcpy(h.key, key.data(), sizeof h.key);
  std::error_code ec;
  fs::create_directories(entry.parent_path(), ec);
  // Another process may write the same entry: each writes its own file, the rename is atomic.
  const fs::path temporary = entry.string() + ".tmp" + std::to_string(::getpid());
  // The payload is hashed as it is written; the header, written last,
  // carries its size and hash. A failure at any point (the disk full, no
  // memory) removes the temporary file and only leaves the scene unkept.
  struct WriteFailed {};
  try {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw WriteFailed{};
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    const std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> hash(XXH3_createState(), XXH3_freeState);
    if (!hash || XXH3_128bits_reset(hash.get()) != XXH_OK) throw std::bad_alloc();
    parsed::encodeScene(scene, [&](std::span<const std::uint8_t> piece) {
      XXH3_128bits_update(hash.get(), piece.data(), piece.size());
      out.write(reinterpret_cast<const char*>(piece.data()), static_cast<std::streamsize>(piece.size()));
      if (!out) throw WriteFailed{};  // stop encoding gigabytes nobody can keep
      h.payloadBytes += piece.size();
    });
    std::memcpy(h.payloadHash, hex(XXH3_128bits_digest(hash.get())).data(), sizeof h.payloadHash);
    out.seekp(0);
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    out.close();
    if (!out) throw WriteFailed{};
  } catch (const WriteFailed&) {
    why = "cannot write '" + temporary.string() + "'";
    fs::remove(temporary, ec);
    return false;
  } catch (const std::bad_alloc&) {
    why = "out of memory while writing '" + temporary.string() + "'";
    fs::remove(temporary, ec);
    return false;
  }
  // The owner's alone to rewrite, whatever the umask: a load uses such an
  // entry's arrays in place (MappedFile::stable).
  fs::permissions(temporary,
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read, ec);
  fs::rename(temporary, entry, ec);
  if (ec) {
    why = "cannot rename into '" + entry.string() + "': " + ec.message();
    fs::remove(temporary, ec);
    return false;
  }
  return true;
}

}  // namespace tsr::sg::cache
