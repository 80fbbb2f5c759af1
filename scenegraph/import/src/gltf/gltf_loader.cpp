#include "gltf/gltf_loader.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>
#include <system_error>

#include <nlohmann/json.hpp>

#include "gltf/draco_primitive.hpp"
#include "gltf/gltf_validation.hpp"
#include "gltf/meshopt_views.hpp"

namespace tsr::sg::gltf {
namespace {

namespace fs = std::filesystem;

// The size of a regular file within `limit`, or an ImportError that says why not.
std::uint64_t checkedSize(const std::string& path, std::uint64_t limit, const std::string& source) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw ImportError(source, "cannot open '" + path + "': " +
                                  (fs::is_directory(path, ec) ? "it is a directory"
                                   : fs::exists(path, ec)     ? "not a regular file"
                                                              : "no such file"));
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) throw ImportError(source, "cannot read '" + path + "': " + ec.message());
  if (size > limit)
    throw ImportLimitError(source,
                           "'" + path + "' is " + std::to_string(size) + " bytes, more than the limit of " +
                               std::to_string(limit) + " bytes (" + std::to_string(limit >> 20) + " MiB)",
                           ImportLimitError::Limit::FileBytes);
  return size;
}

std::vector<unsigned char> readWholeFile(const std::string& path, std::uint64_t limit, const std::string& source) {
  const std::uint64_t size = checkedSize(path, limit, source);
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    throw ImportError(source, "cannot read '" + path + "'");
  return bytes;
}

// tinygltf's file callbacks, replaced so that external buffers obey the size
// limit, no path goes through wordexp (its default expansion), and nothing
// outside the glTF's own folder is touched: tinygltf also searches the
// working directory, and a uri may climb out through "..".
struct FsContext {
  std::uint64_t limit;
  fs::path base;                            // canonical folder of the glTF file
  std::optional<ImportLimitError> refused;  // rethrown with its kind after tinygltf gives up
  bool readOther = false;                   // read a file besides the source (buffer, image)
};
bool insideBase(const std::string& path, const FsContext& ctx) {
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(path, ec);
  if (ec || ctx.base.empty()) return false;
  const auto [b, r] = std::mismatch(ctx.base.begin(), ctx.base.end(), resolved.begin(), resolved.end());
  return b == ctx.base.end();
}
bool fileExists(const std::string& path, void* user) {
  std::error_code ec;
  return insideBase(path, *static_cast<FsContext*>(user)) && fs::is_regular_file(path, ec);
}
std::string expandPath(const std::string& path, void*) { return path; }
bool readFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* ctx = static_cast<FsContext*>(user);
  try {
    if (!insideBase(path, *ctx)) throw ImportError(path, "'" + path + "' is outside the glTF file's folder; refused");
    *out = readWholeFile(path, ctx->limit, path);
    ctx->readOther = true;
    return true;
  } catch (const ImportLimitError& e) {
    if (!ctx->refused) ctx->refused = e;
    if (err) *err += e.reason() + "\n";
    return false;
  } catch (const ImportError& e) {
    if (err) *err += e.reason() + "\n";
    return false;
  }
}
bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the importer writes no files\n";
  return false;
}

// Keeps the encoded bytes of images given by uri; decoding happens later
// with OpenImageIO. Images in buffer views are not touched here because
// tinygltf hands them over without checking the view against its buffer.
bool keepImageBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                    int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

std::uint32_t readU32(const unsigned char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;  // glTF is little-endian, as are the machines we run on
}

// The JSON chunk of a GLB container, with the header checked.
std::string glbJson(std::span<const unsigned char> bytes, const std::string& source) {
  if (bytes.size() < 20) throw ImportError(source, "GLB file too short for its header");
  if (readU32(&bytes[4]) != 2)
    throw ImportError(source, "GLB version " + std::to_string(readU32(&bytes[4])) + " is not supported (only 2)");
  const std::uint64_t length = readU32(&bytes[8]);
  if (length > bytes.size())
    throw ImportError(source, "GLB header says " + std::to_string(length) + " bytes but the file has " +
                                  std::to_string(bytes.size()));
  const std::uint64_t jsonLength = readU32(&bytes[12]);
  if (readU32(&bytes[16]) != 0x4E4F534Au) throw ImportError(source, "GLB first chunk is not JSON");
  if (20 + jsonLength > length) throw ImportError(source, "GLB JSON chunk runs past the end of the file");
  // tinygltf checks the binary chunk without its 8-byte header: checked here whole.
  const std::uint64_t bin = 20 + jsonLength;
  if (bin < length) {
    if (bin + 8 > length) throw ImportError(source, "GLB second chunk's header runs past the end of the file");
    if (bin + 8 + std::uint64_t{readU32(&bytes[bin])} > length)
      throw ImportError(source, "GLB binary chunk runs past the end of the file");
  }
  return std::string(reinterpret_cast<const char*>(&bytes[20]), static_cast<std::size_t>(jsonLength));
}

// Counts JSON values without building them and stops at the limit, so a
// document of 100 million array elements costs a scan, not gigabytes.
class ValueCounter : public nlohmann::json_sax<nlohmann::json> {
 public:
  explicit ValueCounter(std::uint64_t limit) : limit_(limit) {}
  bool overLimit() const { return count_ > limit_; }
  const std::string& error() const { return error_; }

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return value(); }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return value(); }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    error_ = e.what();
    return false;
  }

 private:
  bool value() { return ++count_ <= limit_; }
  std::uint64_t limit_;
  std::uint64_t count_ = 0;
  std::string error_;
};

// Refuses JSON with more values than the limit (or malformed JSON) before
// anything is parsed into memory.
void scanJson(const char* first, const char* last, std::uint64_t limit, const std::string& source) {
  ValueCounter counter(limit);
  if (nlohmann::json::sax_parse(first, last, &counter)) return;
  if (counter.overLimit())
    throw ImportLimitError(source,
                           "the JSON holds more than " + std::to_string(limit) +
                               " values (numbers, strings, array elements, object members), the limit; "
                               "refused before parsing",
                           ImportLimitError::Limit::JsonValues);
  throw ImportError(source, "invalid JSON: " + counter.error());
}

// The GLB container again around another JSON chunk (padded with spaces to
// four bytes, as the format asks); the chunks after it are copied as they
// are. The header was checked by glbJson.
std::vector<unsigned char> glbWithJson(std::span<const unsigned char> bytes, std::string json) {
  while (json.size() % 4) json.push_back(' ');
  const std::size_t rest = 20 + std::size_t{readU32(&bytes[12])}, length = readU32(&bytes[8]);
  const std::size_t total = 20 + json.size() + (length - rest);
  std::vector<unsigned char> out(total);
  auto put = [&](std::size_t at, std::uint32_t v) { std::memcpy(&out[at], &v, 4); };
  std::memcpy(out.data(), "glTF", 4);
  put(4, 2);
  put(8, static_cast<std::uint32_t>(total));
  put(12, static_cast<std::uint32_t>(json.size()));
  put(16, 0x4E4F534Au);
  std::memcpy(&out[20], json.data(), json.size());
  std::memcpy(out.data() + 20 + json.size(), bytes.data() + rest, length - rest);  // may be no bytes at all
  return out;
}

}  // namespace

MappedFile mapSource(const std::string& path, const ImportOptions& options) {
  const std::uint64_t limit = std::min<std::uint64_t>(options.maxFileBytes, 0xFFFFFFFFu);
  checkedSize(path, limit, path);
  MappedFile file;
  try {
    file = MappedFile(path);
  } catch (const std::system_error& e) {
    throw ImportError(path, e.what());
  }
  // The file may have grown since it was sized: the limit holds for what was mapped.
  if (file.bytes().size() > limit)
    throw ImportLimitError(
        path, "'" + path + "' grew past the limit of " + std::to_string(limit) + " bytes while it was read",
        ImportLimitError::Limit::FileBytes);
  return file;
}

LoadedFile loadFile(const std::string& path, const ImportOptions& options) {
  const MappedFile file = mapSource(path, options);
  return loadBytes(file.bytes(), path, fs::path(path).parent_path().string(), options);
}

LoadedFile loadBytes(std::span<const unsigned char> bytes, const std::string& source, const std::string& baseDir,
                     const ImportOptions& options) {
  const std::uint64_t limit = std::min<std::uint64_t>(options.maxFileBytes, 0xFFFFFFFFu);
  if (bytes.size() > limit)
    throw ImportLimitError(source,
                           std::to_string(bytes.size()) + " bytes, more than the limit of " + std::to_string(limit) +
                               " bytes (" + std::to_string(limit >> 20) + " MiB)",
                           ImportLimitError::Limit::FileBytes);
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;

  const std::string glb = binary ? glbJson(bytes, source) : std::string();
  const char* first = binary ? glb.data() : reinterpret_cast<const char*>(bytes.data());
  const char* last = first + (binary ? glb.size() : bytes.size());
  scanJson(first, last, options.maxJsonValues, source);

  DracoIndices dracoIndices;
  std::vector<MeshoptView> meshoptViews;
  std::string rewritten;  // the document without Draco primitives' indices, when it has any
  std::vector<unsigned char> rewrittenGlb;
  {
    nlohmann::json doc;  // freed before tinygltf builds its own
    try {
      doc = nlohmann::json::parse(first, last);
    } catch (const nlohmann::json::exception& e) {
      throw ImportError(source, std::string("invalid JSON: ") + e.what());
    }
    checkJsonTypes(doc, source);
    checkUris(doc, source);
    checkDeclaredSizes(doc, limit, source);
    dracoIndices = takeDracoIndices(doc, source);
    meshoptViews = takeMeshoptViews(doc, source);
    if (!dracoIndices.empty() || !meshoptViews.empty()) {
      rewritten = doc.dump();
      if (binary) rewrittenGlb = glbWithJson(bytes, std::move(rewritten));
    }
  }
  if (!rewrittenGlb.empty()) bytes = rewrittenGlb;
  const std::string_view text = !rewritten.empty()
                                    ? std::string_view(rewritten)
                                    : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());

  tinygltf::TinyGLTF loader;
  std::error_code ec;
  FsContext ctx{limit, fs::weakly_canonical(baseDir.empty() ? fs::path(".") : fs::path(baseDir), ec), std::nullopt};
  if (ec) ctx.base.clear();  // no folder: every external file is refused
  loader.SetFsCallbacks({&fileExists, &expandPath, &readFile, &refuseWrite, &ctx});
  loader.SetImageLoader(&keepImageBytes, nullptr);
  loader.SetPreserveImageChannels(true);

  LoadedFile out;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&out.model, &err, &warn, bytes.data(),
                                                       static_cast<unsigned>(bytes.size()), baseDir)
                         : loader.LoadASCIIFromString(&out.model, &err, &warn, text.data(),
                                                      static_cast<unsigned>(text.size()), baseDir);
  while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
  // Messages stay on one line: callers print them as one.
  for (std::size_t p = err.find('\n'); p != std::string::npos; p = err.find('\n', p)) err.replace(p, 1, "; ");
  // tinygltf may report success with an error message: either is a failure.
  if (ctx.refused) throw *ctx.refused;
  if (!ok || !err.empty()) throw ImportError(source, err.empty() ? "tinygltf could not load the file" : err);
  std::size_t start = 0;
  while (start < warn.size()) {
    std::size_t end = warn.find('\n', start);
    if (end == std::string::npos) end = warn.size();
    if (end > start) out.warnings.push_back(warn.substr(start, end - start));
    start = end + 1;
  }
  checkRequiredExtensions(out.model, source);
  decodeMeshoptViews(out.model, meshoptViews, limit, source);
  checkNodeGraph(out.model, source);
  out.readOtherFiles = ctx.readOther;
  out.dracoIndices = std::move(dracoIndices);
  return out;
}

}  // namespace tsr::sg::gltf
