// tessera-cull's streamed preview (/v1/preview, a WebSocket) and the web
// client's files, over real connections on 127.0.0.1: frames refine the
// resting view to the sample limit and show the same picture the path
// tracer renders here; a new view replaces the old one's frames; a bad
// message gets an error and the stream goes on; the page is served, and
// no path leaves its folders.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "../cluster/node_process.hpp"
#include "backends.hpp"
#include "cull_http.hpp"
#include "scene/scene_session.hpp"
#include "tsr/med/image_file.hpp"

namespace {

namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;
using nlohmann::json;
using tsr::app::test::cornellView;
using tsr::app::test::request;

constexpr int kSampleLimit = 8;

struct Frame {
  std::uint32_t seq = 0, samples = 0, width = 0, height = 0;
  tsr::med::FrameBuffer image;
  std::string text;  // a text message instead of a frame
};

class PreviewClient {
 public:
  explicit PreviewClient(std::uint16_t port, const std::string& target = "/v1/preview") : ws_(io_) {
    ws_.next_layer().connect({boost::asio::ip::make_address("127.0.0.1"), port});
    ws_.handshake("127.0.0.1", target);
  }
  // The connection's bytes as they come, unparsed (no pong is sent), until it closes.
  std::string readRawUntilClosed(boost::system::error_code& ec) {
    timeval timeout{15, 0};
    setsockopt(ws_.next_layer().native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    std::string bytes;
    char chunk[4096];
    for (;;) {
      const std::size_t n = ws_.next_layer().read_some(boost::asio::buffer(chunk), ec);
      bytes.append(chunk, n);
      if (ec) return bytes;
    }
  }
  void send(const json& message) {
    ws_.text(true);
    ws_.write(boost::asio::buffer(message.dump()));
  }
  Frame next() {
    boost::beast::flat_buffer buffer;
    ws_.read(buffer);
    const std::string bytes = boost::beast::buffers_to_string(buffer.data());
    Frame f;
    if (ws_.got_text()) {
      f.text = bytes;
      return f;
    }
    EXPECT_GT(bytes.size(), 16u);
    auto u32 = [&](int at) {
      std::uint32_t v = 0;
      for (int i = 0; i < 4; ++i) v |= std::uint32_t(std::uint8_t(bytes[at + i])) << (8 * i);
      return v;
    };
    f.seq = u32(0), f.samples = u32(4), f.width = u32(8), f.height = u32(12);
    static std::atomic<int> files{0};
    const auto path = std::filesystem::temp_directory_path() /
                      ("tsr-preview-" + std::to_string(::getpid()) + "-" + std::to_string(files++) + ".png");
    std::ofstream(path, std::ios::binary).write(bytes.data() + 16, std::streamsize(bytes.size() - 16));
    f.image = tsr::med::readImage(path.string());
    std::filesystem::remove(path);
    return f;
  }

 private:
  boost::asio::io_context io_;
  websocket::stream<boost::asio::ip::tcp::socket> ws_;
};

json previewView(int width, int height, float x = 278.0f) {
  json view = cornellView(width, height, 1, x);
  view.erase("max_objects");
  return view;
}

double meanLuminance(const tsr::med::FrameBuffer& fb) {
  double sum = 0;
  for (const auto& p : fb.colour) sum += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
  return sum / double(fb.colour.size());
}

class CullPreview : public ::testing::Test {
 protected:
  CullPreview()
      : service({TSR_CULL_BINARY, "builtin:cornell", "--listen", "127.0.0.1:0", "--threads", "2", "--preview-spp",
                 std::to_string(kSampleLimit)}) {}
  std::uint16_t port() const { return service.address().port; }
  tsr::cluster::test::ListeningProcess service;
};

TEST_F(CullPreview, FramesRefineTheRestingViewToTheLimitAndShowWhatThePathTracerRenders) {
  PreviewClient client(port());
  client.send({{"seq", 7}, {"view", previewView(64, 48)}});
  std::vector<Frame> frames;
  while (frames.empty() || frames.back().samples < kSampleLimit) {
    frames.push_back(client.next());
    ASSERT_TRUE(frames.back().text.empty()) << frames.back().text;
  }
  ASSERT_GE(frames.size(), 2u) << "a first frame early, then better ones";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].seq, 7u);
    EXPECT_EQ(frames[i].width, 64u);
    EXPECT_EQ(frames[i].image.width, 64u);
    EXPECT_EQ(frames[i].image.height, 48u);
    if (i) {
      EXPECT_GT(frames[i].samples, frames[i - 1].samples);
    }
  }
  EXPECT_EQ(frames.front().samples, 1u);

  // The same view, traced here with the service's preview settings (pixel
  // filtering, as every interactive program opens with).
  tsr::app::SceneSession session;
  session.load("builtin:cornell");
  session.publish();
  tsr::med::ViewportRegistry registry;
  tsr::app::registerBackends(registry);
  tsr::med::ContextPool contexts;
  tsr::med::Parameters parameters;
  parameters.set("filter", std::string("pixel"));
  parameters.set("spp", std::int64_t(kSampleLimit));
  auto viewport = registry.create({"embree", session.imported.root, session.imported.background,
                                   registry.parametersFor("embree", parameters), true},
                                  contexts);
  tsr::med::FrameBuffer local;
  viewport->render(session.replica, tsr::app::test::cornellServiceView(session, 64, 48), local, {});
  const std::string path = (std::filesystem::temp_directory_path() / "tsr-preview-local.png").string();
  tsr::med::writeImage(path, local);
  const tsr::med::FrameBuffer expected = tsr::med::readImage(path);  // through the same 8 bits
  const auto& shown = frames.back().image;
  double diff = 0;
  for (std::size_t i = 0; i < shown.colour.size(); ++i)
    diff += std::abs(shown.colour[i].r - expected.colour[i].r) + std::abs(shown.colour[i].g - expected.colour[i].g) +
            std::abs(shown.colour[i].b - expected.colour[i].b);
  diff /= 3.0 * double(shown.colour.size());
  EXPECT_GT(meanLuminance(expected), 0.05) << "a lit picture, not black";
  EXPECT_LT(diff, 0.02) << "the streamed image is the path tracer's picture of the view";
}

TEST_F(CullPreview, ANewViewReplacesTheOldOnesFramesAndBadMessagesGetAnError) {
  PreviewClient client(port());
  client.send({{"seq", 1}, {"view", previewView(48, 32)}});
  EXPECT_EQ(client.next().seq, 1u);
  client.send({{"seq", 2}, {"view", previewView(40, 30, 150.0f)}});
  Frame f;
  do f = client.next();
  while (f.seq == 1);
  EXPECT_EQ(f.seq, 2u);
  EXPECT_EQ(f.image.width, 40u);
  while (f.samples < kSampleLimit) {
    f = client.next();
    EXPECT_EQ(f.seq, 2u) << "no frame of the old view after the new view's first";
  }
  client.send({{"seq", 3}, {"view", {{"camera", "nowhere"}}}});
  f = client.next();
  EXPECT_NE(f.text.find("camera: expected an object"), std::string::npos) << f.text;
  client.send({{"seq", 4}, {"view", previewView(100000, 32)}});
  f = client.next();
  EXPECT_NE(f.text.find("width"), std::string::npos) << f.text;
  client.send({{"seq", 5}, {"view", previewView(2000, 2000)}});
  f = client.next();
  EXPECT_NE(f.text.find("previews take at most"), std::string::npos) << f.text;
  client.send({{"seq", 6}, {"view", previewView(24, 24)}});
  f = client.next();
  EXPECT_EQ(f.seq, 6u) << "the stream goes on after bad messages";
  EXPECT_EQ(f.image.width, 24u);
}

TEST_F(CullPreview, ThePageAndItsSceneAreServedAndNoPathLeavesTheirFolders) {
  const auto page = request(port(), http::verb::get, "/");
  ASSERT_EQ(page.status, 200u);
  EXPECT_NE(page.contentType.find("text/html"), std::string::npos);
  EXPECT_NE(page.body.find("importmap"), std::string::npos);
  const auto module = request(port(), http::verb::get, "/src/main.js");
  EXPECT_EQ(module.status, 200u);
  EXPECT_NE(module.contentType.find("javascript"), std::string::npos);
  EXPECT_EQ(request(port(), http::verb::get, "/three/build/three.module.js").status, 200u)
      << "three.js from web/node_modules (npm ci in scripts/install-deps.sh)";
  for (const char* path : {"/src/../../CMakeLists.txt", "/src/.hidden.js", "/src//main.js", "/three/../package.json",
                           "/src/main.cpp", "/src/%2e%2e/x.js"})
    EXPECT_EQ(request(port(), http::verb::get, path).status, 400u) << path;
  EXPECT_EQ(request(port(), http::verb::get, "/src/nothing.js").status, 404u);

  const auto scene = request(port(), http::verb::get, "/v1/scene");
  ASSERT_EQ(scene.status, 200u) << scene.body;
  const json s = json::parse(scene.body);
  EXPECT_EQ(s["total_triangles"].get<std::uint64_t>(), 4448u);
  EXPECT_TRUE(s["preview"].get<bool>());
  EXPECT_EQ(s["camera"]["position"].size(), 3u);
  EXPECT_EQ(s["background"]["kind"], "color") << "the page matches the path tracer's backdrop";
  EXPECT_EQ(s["background"]["color"], json::array({0.0, 0.0, 0.0})) << "the Cornell box's is black";
  EXPECT_EQ(request(port(), http::verb::get, "/v1/preview").status, 426u) << "a WebSocket, not a page";
}

// --cluster: the same stream, rendered by two tessera-node processes
// sharing the frame (the cooperative config), shows the same picture.
TEST(CullPreviewCluster, PreviewsRenderOnTheNodesTheConfigNames) {
  auto nodes = tsr::cluster::test::startNodes(2);
  const std::string addresses = nodes[0]->address().host + ":" + std::to_string(nodes[0]->address().port) + "," +
                                nodes[1]->address().host + ":" + std::to_string(nodes[1]->address().port);
  tsr::cluster::test::ListeningProcess service({TSR_CULL_BINARY, "builtin:cornell", "--listen", "127.0.0.1:0",
                                                "--threads", "1", "--preview-spp", std::to_string(kSampleLimit),
                                                "--cluster", std::string(TSR_CONFIGS) + "/cooperative-2.json",
                                                "--nodes", addresses});
  PreviewClient remote(service.address().port);
  remote.send({{"seq", 1}, {"view", previewView(64, 48)}});
  Frame far;
  do {
    far = remote.next();
    ASSERT_TRUE(far.text.empty()) << far.text;
  } while (far.samples < kSampleLimit);
  EXPECT_EQ(far.seq, 1u);
  EXPECT_EQ(far.image.width, 64u);

  tsr::cluster::test::ListeningProcess local({TSR_CULL_BINARY, "builtin:cornell", "--listen", "127.0.0.1:0",
                                              "--threads", "1", "--preview-spp", std::to_string(kSampleLimit)});
  PreviewClient here(local.address().port);
  here.send({{"seq", 1}, {"view", previewView(64, 48)}});
  Frame near;
  do near = here.next();
  while (near.samples < kSampleLimit);
  EXPECT_GT(meanLuminance(far.image), 0.05);
  EXPECT_NEAR(meanLuminance(far.image), meanLuminance(near.image), 0.1 * meanLuminance(near.image))
      << "the nodes' picture is the local one's";
}

TEST(CullPreviewAccess, WithATokenTheStreamAsksForItAndThePageDoesNot) {
  tsr::cluster::test::TokenFile token("preview-token");
  tsr::cluster::test::ListeningProcess guarded(
      {TSR_CULL_BINARY, "builtin:cornell", "--listen", "127.0.0.1:0", "--token-file", token.path(), "--threads", "1"});
  const std::uint16_t port = guarded.address().port;
  EXPECT_EQ(request(port, http::verb::get, "/").status, 200u);
  EXPECT_EQ(request(port, http::verb::get, "/v1/scene").status, 401u);
  EXPECT_EQ(request(port, http::verb::get, "/v1/scene?access_token=preview-token").status, 200u);
  EXPECT_THROW(PreviewClient(port, "/v1/preview"), boost::system::system_error);
  PreviewClient client(port, "/v1/preview?access_token=preview-token");
  client.send({{"seq", 1}, {"view", previewView(16, 16)}});
  EXPECT_EQ(client.next().seq, 1u);
}

// A stream that answers no ping is closed after --ping-timeout; a second
// stream from the same address over --max-previews-per-address gets 429.
TEST(CullPreviewLimits, AStreamThatAnswersNoPingClosesAndOneAddressHoldsItsShare) {
  tsr::cluster::test::ListeningProcess service({TSR_CULL_BINARY, "builtin:cornell", "--listen", "127.0.0.1:0",
                                                "--threads", "1", "--ping-timeout", "1", "--max-previews-per-address",
                                                "1"});
  const std::uint16_t port = service.address().port;
  PreviewClient first(port);
  try {
    PreviewClient second(port);
    ADD_FAILURE() << "a second stream from 127.0.0.1 was accepted";
  } catch (const boost::system::system_error& e) {
    EXPECT_EQ(e.code(), websocket::error::upgrade_declined) << e.what();
  }
  // The first one never reads, so it never answers the service's ping: the
  // raw socket sees the ping, then the end, within the timeout and a margin.
  const auto start = std::chrono::steady_clock::now();
  boost::system::error_code ec;
  std::string raw = first.readRawUntilClosed(ec);
  EXPECT_TRUE(ec == boost::asio::error::eof || ec == boost::asio::error::connection_reset) << ec.message();
  ASSERT_GE(raw.size(), 2u);
  EXPECT_EQ(std::uint8_t(raw[0]), 0x89u) << "a ping frame first";
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  // The address's share is free again (a moment after the client sees the end).
  std::unique_ptr<PreviewClient> again;
  for (int attempt = 0; !again && attempt < 50; ++attempt) {
    try {
      again = std::make_unique<PreviewClient>(port);
    } catch (const boost::system::system_error&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  ASSERT_TRUE(again) << "the stream's share was not given back";
  again->send({{"seq", 7}, {"view", previewView(16, 16)}});
  EXPECT_EQ(again->next().seq, 7u);
}

}  // namespace
