#pragma once
// The shared token and the HMAC-SHA256 proofs built from it. The token
// never travels: each side proves it knows it by keying an HMAC over both
// sides' fresh nonces and a role label, so a proof cannot be replayed to
// another connection or reflected back at its sender.
#include <string>

#include "tsr/cluster/messages.hpp"

namespace tsr::cluster {

class TokenError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads a token file: its bytes with one trailing newline removed. Throws
// TokenError for a missing, empty or over-long (> 4 KiB) file.
std::string readTokenFile(const std::string& path);

Nonce randomNonce();
Digest hmacSha256(const std::string& key, std::span<const std::uint8_t> message);

// role is "node" or "client"; `own` is the prover's nonce, `peer` the verifier's.
Digest proof(const std::string& token, const char* role, const Nonce& verifierNonce, const Nonce& proverNonce);
// Constant-time comparison.
bool sameDigest(const Digest& a, const Digest& b);

}  // namespace tsr::cluster
