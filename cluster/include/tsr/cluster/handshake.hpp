#pragma once
// Both sides of the handshake as plain state machines (no sockets), so the
// rules can be tested byte for byte:
//   client -> Hello(version, client nonce)
//   node   -> Challenge(node nonce, proof_node)  or Reject (version)
//   client -> Auth(proof_client)                  (after checking proof_node)
//   node   -> Welcome(name, threads, back-ends)   or Reject (token)
// proof_x = HMAC-SHA256(token, "tessera-x" 0 verifier-nonce prover-nonce).
#include <optional>
#include <string>

#include "tsr/cluster/messages.hpp"

namespace tsr::cluster {

class ClientHandshake {
 public:
  ClientHandshake(std::string token, std::string clientName, std::uint8_t version = kProtocolVersion);
  Frame hello() const;
  // Checks the node's proof; returns the Auth frame. Throws ProtocolError
  // (AuthFailed when the node does not know the token, Rejected on Reject).
  Frame onChallenge(const Message& message);
  // Returns the node's welcome; throws ProtocolError on Reject.
  Welcome onWelcome(const Message& message);

 private:
  std::string token_;
  Nonce nonce_;
  Nonce nodeNonce_{};
  Hello hello_;
};

class NodeHandshake {
 public:
  NodeHandshake(std::string token, Welcome welcome);
  // Either a Challenge (reply, continue) or a Reject (reply, then close).
  struct Step {
    Frame reply;
    bool accepted = false;
    std::string reason;  // why, when not accepted
  };
  Step onHello(const Message& message);
  Step onAuth(const Message& message);
  bool done() const { return done_; }

 private:
  std::string token_;
  Welcome welcome_;
  Nonce nonce_;
  Nonce clientNonce_{};
  bool challenged_ = false;
  bool done_ = false;
};

}  // namespace tsr::cluster
