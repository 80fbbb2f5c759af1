#pragma once
// Checks on a glTF document that tinygltf does not make: JSON types of the
// properties we read, required extensions, and a node graph that is a
// forest. Each throws ImportError naming the offending element.
#include <cstdint>
#include <string>

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

namespace tsr::sg::gltf {

// The extensions the importer implements; others in extensionsRequired fail.
bool isSupportedExtension(const std::string& name);

// Types of every property the importer reads, before tinygltf (which
// silently ignores properties of the wrong type) sees the document.
void checkJsonTypes(const nlohmann::json& doc, const std::string& source);

// Buffer and image uris name files inside the glTF's folder or are data:
// uris; a scheme, an absolute path or a ".." that climbs out is refused
// before any file is opened (after percent-decoding, as tinygltf does).
void checkUris(const nlohmann::json& doc, const std::string& source);

// Buffers that declare more bytes than a file may hold are refused before
// tinygltf decodes or reads them (ImportLimitError, FileBytes).
void checkDeclaredSizes(const nlohmann::json& doc, std::uint64_t maxFileBytes, const std::string& source);

void checkRequiredExtensions(const tinygltf::Model& model, const std::string& source);

// Child indices in range, no node with two parents, no cycles.
void checkNodeGraph(const tinygltf::Model& model, const std::string& source);

}  // namespace tsr::sg::gltf
