// tessera-cull over real HTTP on 127.0.0.1: the ranking is the coverage
// renderer's for the same view, objects load with tinygltf where they sit
// in the scene, bad requests get a 4xx and the service goes on, and eight
// clients at once get the answers one client gets.
#include <gtest/gtest.h>

#include <future>
#include <thread>

#include <tiny_gltf.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "../cluster/node_process.hpp"
#include "backends.hpp"
#include "cull_http.hpp"
#include "scene/scene_session.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/scene_flattening.hpp"

namespace {

namespace http = boost::beast::http;
using nlohmann::json;

using tsr::app::test::cornellView;
using tsr::app::test::Reply;
using tsr::app::test::request;

class CullService : public ::testing::Test {
 protected:
  CullService() : service({TSR_CULL_BINARY, "builtin:cornell", "--listen", "127.0.0.1:0", "--threads", "1"}) {}
  std::uint16_t port() const { return service.address().port; }
  json cull(const json& view) {
    const Reply r = request(port(), http::verb::post, "/v1/cull", view.dump());
    EXPECT_EQ(r.status, 200u) << r.body;
    return json::parse(r.body);
  }
  tsr::cluster::test::ListeningProcess service;
};

TEST_F(CullService, RankingEqualsTheCoverageRenderersForTheSameView) {
  const json answer = cull(cornellView(96, 64, 100));
  // The same view rendered here by the coverage back-end, ranked.
  tsr::app::SceneSession session;
  session.load("builtin:cornell");
  session.publish();
  tsr::med::ViewportRegistry registry;
  tsr::app::registerBackends(registry);
  tsr::med::ContextPool contexts;
  auto viewport = registry.create({"coverage", session.imported.root, session.imported.background, {}, true}, contexts);
  tsr::med::FrameBuffer image;
  tsr::med::RenderControl control;
  control.outputs = std::vector<std::string>{tsr::med::kIdOutput};
  viewport->render(session.replica, tsr::app::test::cornellServiceView(session, 96, 64), image, control);
  const auto ranked = tsr::med::rankObjects(image, session.replica.scene());
  ASSERT_EQ(answer["objects"].size(), ranked.size());
  ASSERT_GE(ranked.size(), 5u);
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    EXPECT_EQ(answer["objects"][i]["id"].get<std::uint64_t>(), ranked[i].id) << i;
    EXPECT_EQ(answer["objects"][i]["pixels"].get<std::uint64_t>(), ranked[i].pixels) << i;
    EXPECT_EQ(answer["objects"][i]["name"].get<std::string>(), ranked[i].name) << i;
  }
  EXPECT_NEAR(answer["covered_fraction"].get<double>(), 1.0 - double(tsr::med::backgroundPixels(image)) / (96.0 * 64.0),
              1e-12);
  EXPECT_EQ(answer["total_triangles"].get<std::uint64_t>(), 4448u);
  // max_objects keeps the top K.
  const json top2 = cull(cornellView(96, 64, 2));
  ASSERT_EQ(top2["objects"].size(), 2u);
  EXPECT_EQ(top2["objects"][0]["id"], answer["objects"][0]["id"]);
  EXPECT_EQ(top2["objects"][1]["id"], answer["objects"][1]["id"]);
}

TEST_F(CullService, ObjectsLoadWithTinygltfWhereTheySitInTheScene) {
  tsr::app::SceneSession session;
  session.load("builtin:cornell");
  const tsr::med::FlatScene flat = tsr::med::flatten(session.source, session.imported.root);
  for (const auto& o : cull(cornellView(96, 64, 100))["objects"]) {
    const auto id = o["id"].get<tsr::sg::ContainerId>();
    const Reply r = request(port(), http::verb::get, "/v1/objects/" + std::to_string(id) + ".glb");
    ASSERT_EQ(r.status, 200u) << r.body;
    EXPECT_FALSE(r.etag.empty());
    EXPECT_EQ(request(port(), http::verb::get, "/v1/objects/" + std::to_string(id) + ".glb", {}, r.etag).status, 304u)
        << "cacheable: the ETag answers 304";
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(r.body.data()),
                                            static_cast<unsigned>(r.body.size())))
        << err;
    // The glb's position bounds equal the object's world-space bounds.
    glm::vec3 lo(1e30f), hi(-1e30f), wantLo(1e30f), wantHi(-1e30f);
    for (const auto& mesh : model.meshes) {
      const auto& accessor = model.accessors[mesh.primitives[0].attributes.at("POSITION")];
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], float(accessor.minValues[c]));
        hi[c] = std::max(hi[c], float(accessor.maxValues[c]));
      }
    }
    std::uint64_t triangles = 0;
    for (const auto& instance : flat.instances) {
      if (tsr::med::objectOf(session.source, instance) != id) continue;
      const auto* g = session.source.find<tsr::sg::Geometry>(instance.id);
      triangles += g->triangleCount();
      for (const auto& p : g->positions()) {
        const glm::vec3 w = glm::vec3(instance.world * glm::vec4(p, 1.0f));
        wantLo = glm::min(wantLo, w);
        wantHi = glm::max(wantHi, w);
      }
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(lo[c], wantLo[c], 1e-3f) << o["name"];
      EXPECT_NEAR(hi[c], wantHi[c], 1e-3f) << o["name"];
    }
    EXPECT_EQ(o["triangles"].get<std::uint64_t>(), triangles) << o["name"];
  }
}

TEST_F(CullService, MalformedRequestsGet4xxAndTheServiceGoesOn) {
  const auto post = [&](const std::string& body) { return request(port(), http::verb::post, "/v1/cull", body); };
  EXPECT_EQ(post("{not json").status, 400u);
  EXPECT_EQ(post("[]").status, 400u);
  EXPECT_EQ(post(cornellView(100000, 64, 4).dump()).status, 400u) << "absurd size";
  EXPECT_EQ(post(cornellView(64, 64, 0).dump()).status, 400u);
  json nan = cornellView(64, 64, 4);
  nan["camera"]["position"] = {1e30, 0, 0};
  EXPECT_EQ(post(nan.dump()).status, 400u);
  json same = cornellView(64, 64, 4);
  same["camera"]["target"] = same["camera"]["position"];
  EXPECT_EQ(post(same.dump()).status, 400u);
  json extra = cornellView(64, 64, 4);
  extra["bogus"] = 1;
  const Reply named = post(extra.dump());
  EXPECT_EQ(named.status, 400u);
  EXPECT_NE(named.body.find("unknown field 'bogus'"), std::string::npos) << named.body;
  EXPECT_EQ(post(std::string(100 * 1024, ' ')).status, 400u) << "a body over 64 KiB";
  for (const char* path : {"/v1/objects/99999.glb"})
    EXPECT_EQ(request(port(), http::verb::get, path).status, 404u) << path;
  for (const char* path : {"/v1/objects/../../etc/passwd", "/v1/objects/01.glb", "/v1/objects/-2.glb",
                           "/v1/objects/2.glb/../3.glb", "/v1/objects/.glb"})
    EXPECT_EQ(request(port(), http::verb::get, path).status, 400u) << path;
  EXPECT_EQ(request(port(), http::verb::get, "/nothing").status, 404u);
  EXPECT_EQ(request(port(), http::verb::get, "/v1/cull").status, 405u);
  // And it still answers.
  EXPECT_FALSE(cull(cornellView(32, 32, 3))["objects"].empty());
}

TEST_F(CullService, EightConcurrentClientsGetTheAnswersOneClientGets) {
  std::vector<json> alone;
  for (int v = 0; v < 8; ++v) alone.push_back(cull(cornellView(48, 32, 10, 200.0f + 20.0f * float(v))));
  std::vector<std::future<std::vector<json>>> clients;
  for (int c = 0; c < 8; ++c)
    clients.push_back(std::async(std::launch::async, [&, c] {
      std::vector<json> seen;
      for (int round = 0; round < 3; ++round) {
        const int v = (c + round) % 8;
        const Reply r =
            request(port(), http::verb::post, "/v1/cull", cornellView(48, 32, 10, 200.0f + 20.0f * float(v)).dump());
        seen.push_back(r.status == 200 ? json::parse(r.body) : json{{"status", r.status}});
      }
      return seen;
    }));
  for (int c = 0; c < 8; ++c) {
    const auto seen = clients[c].get();
    for (int round = 0; round < 3; ++round) EXPECT_EQ(seen[round], alone[(c + round) % 8]) << c << " " << round;
  }
}

// As tessera-node: beyond loopback only with a token, and then every
// request proves it.
TEST(CullServiceAccess, ATokenGuardsItAndNoTokenMeansLoopbackOnly) {
  EXPECT_THROW(tsr::cluster::test::ListeningProcess({TSR_CULL_BINARY, "builtin:cornell", "--listen", "0.0.0.0:0"}),
               std::runtime_error);
  tsr::cluster::test::TokenFile token("cull token");
  tsr::cluster::test::ListeningProcess guarded(
      {TSR_CULL_BINARY, "builtin:cornell", "--listen", "127.0.0.1:0", "--token-file", token.path()});
  const std::string body = cornellView(16, 16, 2).dump();
  const std::uint16_t port = guarded.address().port;
  EXPECT_EQ(request(port, http::verb::post, "/v1/cull", body).status, 401u);
  EXPECT_EQ(request(port, http::verb::post, "/v1/cull", body, {}, "Bearer wrong").status, 401u);
  EXPECT_EQ(request(port, http::verb::post, "/v1/cull", body, {}, "Bearer cull token").status, 200u);
}

}  // namespace
