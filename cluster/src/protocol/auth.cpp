#include "tsr/cluster/auth.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>

namespace tsr::cluster {

std::string readTokenFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw TokenError("token file '" + path + "' is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TokenError("cannot read token file '" + path + "'");
  std::string token;
  char c;
  while (in.get(c)) {
    token.push_back(c);
    if (token.size() > 4097) throw TokenError("token file '" + path + "' is longer than 4 KiB");
  }
  if (!token.empty() && token.back() == '\n') token.pop_back();
  if (!token.empty() && token.back() == '\r') token.pop_back();
  if (token.empty()) throw TokenError("token file '" + path + "' is empty");
  if (token.size() > 4096) throw TokenError("token file '" + path + "' is longer than 4 KiB");
  return token;
}

Nonce randomNonce() {
  Nonce n;
  if (RAND_bytes(n.data(), static_cast<int>(n.size())) != 1) throw std::runtime_error("RAND_bytes failed");
  return n;
}

Digest hmacSha256(const std::string& key, std::span<const std::uint8_t> message) {
  Digest out{};
  unsigned int length = 0;
  // An empty key is legal for HMAC; OpenSSL wants a non-null pointer for it.
  static const unsigned char kEmpty = 0;
  const void* k = key.empty() ? static_cast<const void*>(&kEmpty) : static_cast<const void*>(key.data());
  if (!HMAC(EVP_sha256(), k, static_cast<int>(key.size()), message.data(), message.size(), out.data(), &length) ||
      length != out.size())
    throw std::runtime_error("HMAC-SHA256 failed");
  return out;
}

Digest proof(const std::string& token, const char* role, const Nonce& verifierNonce, const Nonce& proverNonce) {
  std::vector<std::uint8_t> message;
  std::string label = std::string("tessera-") + role;
  message.insert(message.end(), label.begin(), label.end());
  message.push_back(0);
  message.insert(message.end(), verifierNonce.begin(), verifierNonce.end());
  message.insert(message.end(), proverNonce.begin(), proverNonce.end());
  return hmacSha256(token, message);
}

bool sameDigest(const Digest& a, const Digest& b) { return CRYPTO_memcmp(a.data(), b.data(), a.size()) == 0; }

}  // namespace tsr::cluster
