#include "tsr/cluster/handshake.hpp"

#include "tsr/cluster/auth.hpp"
#include "tsr/cluster/protocol_error.hpp"

namespace tsr::cluster {

using Kind = ProtocolError::Kind;

namespace {
[[noreturn]] void throwRejected(const Message& message) {
  throw ProtocolError(Kind::Rejected, "node refused: " + parse<Reject>(message).reason);
}
}  // namespace

ClientHandshake::ClientHandshake(std::string token, std::string clientName, std::uint8_t version)
    : token_(std::move(token)), nonce_(randomNonce()) {
  hello_.version = version;
  hello_.clientNonce = nonce_;
  hello_.clientName = std::move(clientName);
}

Frame ClientHandshake::hello() const { return makeFrame(hello_); }

Frame ClientHandshake::onChallenge(const Message& message) {
  if (message.type == Reject::kType) throwRejected(message);
  Challenge c = parse<Challenge>(message);
  if (!sameDigest(c.nodeProof, proof(token_, "node", nonce_, c.nodeNonce)))
    throw ProtocolError(Kind::AuthFailed, "the node does not know our token");
  nodeNonce_ = c.nodeNonce;
  return makeFrame(Auth{proof(token_, "client", nodeNonce_, nonce_)});
}

Welcome ClientHandshake::onWelcome(const Message& message) {
  if (message.type == Reject::kType) throwRejected(message);
  return parse<Welcome>(message);
}

NodeHandshake::NodeHandshake(std::string token, Welcome welcome)
    : token_(std::move(token)), welcome_(std::move(welcome)), nonce_(randomNonce()) {}

NodeHandshake::Step NodeHandshake::onHello(const Message& message) {
  if (challenged_) throw ProtocolError(Kind::Unexpected, "Hello sent twice");
  Hello h = parse<Hello>(message);
  if (h.version != kProtocolVersion) {
    std::string why = "protocol version " + std::to_string(h.version) + " not supported; this node speaks " +
                      std::to_string(kProtocolVersion);
    return {makeFrame(Reject{why}), false, why};
  }
  challenged_ = true;
  clientNonce_ = h.clientNonce;
  return {makeFrame(Challenge{nonce_, proof(token_, "node", clientNonce_, nonce_)}), true, {}};
}

NodeHandshake::Step NodeHandshake::onAuth(const Message& message) {
  if (!challenged_ || done_) throw ProtocolError(Kind::Unexpected, "Auth before Hello or after the handshake");
  Auth a = parse<Auth>(message);
  if (!sameDigest(a.clientProof, proof(token_, "client", nonce_, clientNonce_))) {
    std::string why = "authentication failed: wrong token";
    return {makeFrame(Reject{why}), false, why};
  }
  done_ = true;
  return {makeFrame(welcome_), true, {}};
}

}  // namespace tsr::cluster
