#pragma once
// The service's bearer token, checked in constant time: the presented and
// the expected token are each keyed into an HMAC under a key drawn at
// start, and the digests compared with the cluster handshake's
// constant-time comparison, so neither the first differing byte nor the
// token's length shows in how long a refusal takes.
#include <string>
#include <string_view>

#include "tsr/cluster/messages.hpp"

namespace tsr::app {

class AccessToken {
 public:
  explicit AccessToken(const std::string& token);  // empty: nothing is asked
  bool required() const { return required_; }
  // True when no token is required, or `presented` is the token.
  bool accepts(std::string_view presented) const;

 private:
  std::string key_;
  cluster::Digest expected_{};
  bool required_ = false;
};

}  // namespace tsr::app
