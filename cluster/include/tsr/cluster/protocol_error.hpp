#pragma once
// Everything that can go wrong with a peer, typed, so callers can tell a
// wrong token from a broken frame from a peer that went quiet.
#include <stdexcept>
#include <string>

namespace tsr::cluster {

class ProtocolError : public std::runtime_error {
 public:
  enum class Kind {
    BadMagic,         // not our protocol at all
    VersionMismatch,  // our protocol, another version
    UnknownType,      // a message type byte we do not know
    Oversized,        // a length beyond the maximum for its type
    Unexpected,       // a known message at the wrong time or from the wrong side
    Malformed,        // a payload that does not decode
    AuthFailed,       // the peer could not prove it knows the token
    Rejected,         // the node refused us (its reason is the message)
    Timeout,          // the peer went quiet
    Closed,           // the connection ended
  };
  ProtocolError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

const char* name(ProtocolError::Kind kind);

}  // namespace tsr::cluster
