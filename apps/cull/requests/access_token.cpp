#include "requests/access_token.hpp"

#include "tsr/cluster/auth.hpp"

namespace tsr::app {

namespace {

cluster::Digest digestOf(const std::string& key, std::string_view text) {
  return cluster::hmacSha256(key, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

}  // namespace

AccessToken::AccessToken(const std::string& token) : required_(!token.empty()) {
  const cluster::Nonce key = cluster::randomNonce();
  key_.assign(key.begin(), key.end());
  expected_ = digestOf(key_, token);
}

bool AccessToken::accepts(std::string_view presented) const {
  return !required_ || cluster::sameDigest(digestOf(key_, presented), expected_);
}

}  // namespace tsr::app
