// tessera-cull SCENE --listen HOST:PORT [--token-file F] [--backend coverage]
//              [--max-objects K] [--threads N] [--web DIR] [--previews N]
//              [--preview-backend embree] [--preview-spp N]
//              [--cluster CONFIG [--nodes ...] [--node-token-file F]]
//              [limits: --io-threads --max-connections --max-connections-per-address
//               --max-requests-per-address --max-previews-per-address --cull-queue
//               --header-timeout --keepalive-timeout --transfer-timeout --min-rate
//               --ping-timeout]
// The culling service of Schwenk 5.4.3: POST /v1/cull ranks the scene's
// objects by visible coverage for a view, GET /v1/objects/ID.glb serves one
// object, GET / the three.js client, and /v1/preview streams the path
// tracer's image of a resting view (rendered here or on a cluster's nodes).
// Prints "listening on HOST:PORT" (port 0 picks a free one) once it accepts
// connections. Without a token file it listens only on loopback.
#include <sys/resource.h>

#include <filesystem>
#include <iostream>
#include <system_error>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "command_line.hpp"
#include "error_line.hpp"
#include "import_limit_options.hpp"
#include "preview/preview_viewports.hpp"
#include "program_folder.hpp"
#include "program_main.hpp"
#include "requests/web_files.hpp"
#include "service/cull_service.hpp"
#include "service/http_service.hpp"
#include "service_limits.hpp"
#include "tsr/cluster/auth.hpp"
#include "tsr/cluster/node_address.hpp"

namespace {

// The page an installed tessera-cull serves lies beside its bin/
// (share/tessera/web); one run from the build tree serves the sources' web/.
std::string defaultWebFolder() {
  std::error_code ec;
  if (const auto folder = tsr::app::programFolder()) {
    const std::filesystem::path installed = folder->parent_path() / "share" / "tessera" / "web";
    if (std::filesystem::is_regular_file(installed / "index.html", ec)) return installed.string();
  }
  return TSR_WEB_DIR;
}

// Each connection holds a file descriptor: the soft limit goes up to the
// hard one, and the connection limit down to what the descriptors allow
// (a few dozen kept for the scene, the web files and the log).
void fitOpenFiles(tsr::app::ServiceLimits& limits) {
  constexpr rlim_t kReserved = 64;
  rlimit files{};
  if (getrlimit(RLIMIT_NOFILE, &files) != 0) return;
  const rlim_t want = rlim_t(limits.maxConnections) * 2 + kReserved;  // admitted and refused ones
  if (files.rlim_cur < want && files.rlim_cur < files.rlim_max) {
    const rlim_t before = files.rlim_cur;
    files.rlim_cur = files.rlim_max == RLIM_INFINITY ? want : std::min(want, files.rlim_max);
    if (setrlimit(RLIMIT_NOFILE, &files) == 0)
      spdlog::info("open-file limit raised from {} to {} for {} connections", before, files.rlim_cur,
                   limits.maxConnections);
    getrlimit(RLIMIT_NOFILE, &files);
  }
  if (files.rlim_cur != RLIM_INFINITY && files.rlim_cur < want) {
    const int fit = int(std::max<rlim_t>(files.rlim_cur, 2 * kReserved) - kReserved) / 2;
    spdlog::warn("the open-file limit ({}) allows {} connections, not --max-connections {}: raise it (ulimit -n)",
                 files.rlim_cur, fit, limits.maxConnections);
    limits.maxConnections = fit;
  }
}

// What the command line sets.
struct CullOptions {
  std::string scene, listen = "127.0.0.1:0", tokenFile, backend = "coverage";
  std::uint32_t maxObjects = 256;
  std::int64_t threads = 0;
  std::string web = defaultWebFolder(), previewBackend = "embree";
  int previews = 4;
  std::uint32_t previewSpp = 64;
  tsr::app::RenderJob cluster;  // its sequence's --cluster, --nodes and --node-token-file
  tsr::app::ServiceLimits service;
  // The limits' timeouts in seconds as the command line gives them; set into `service` after parsing.
  double headerTimeout = service.headerTimeout.count(), keepAliveTimeout = service.keepAliveTimeout.count(),
         transferTimeout = service.transferTimeout.count(), pingTimeout = service.pingTimeout.count();
  tsr::app::ImportLimitOptions limits;
  tsr::sg::ImportOptions import;
};

// The scene, where to listen, the ranking, the web client, the previews and their cluster.
void addServiceOptions(CLI::App& app, CullOptions& o) {
  app.add_option("scene", o.scene, tsr::app::sceneArgumentHelp())->required();
  app.add_option("--listen", o.listen, "HOST:PORT to listen on (port 0: a free port)")->capture_default_str();
  app.add_option("--token-file", o.tokenFile,
                 "file holding the token clients send as 'Authorization: Bearer TOKEN' (required beyond loopback)");
  app.add_option("--backend", o.backend, "the ranking back-end: one with an object-id output")->capture_default_str();
  app.add_option("--max-objects", o.maxObjects, "the most objects one request may ask for, and the default")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  app.add_option("--threads", o.threads, "threads of the ranking id pass and of the previews (0: all)")
      ->check(CLI::Range(0, 4096));
  app.add_option("--web", o.web, "the web client's folder (index.html, src/, node_modules/three)")
      ->capture_default_str();
  app.add_option("--previews", o.previews, "path-traced previews streamed at once (0: none)")
      ->check(CLI::Range(0, 32))
      ->capture_default_str();
  app.add_option("--preview-backend", o.previewBackend, "the back-end of the streamed previews")->capture_default_str();
  app.add_option("--preview-spp", o.previewSpp, "samples per pixel a preview refines to, then stands")
      ->check(CLI::Range(1u, 65536u))
      ->capture_default_str();
  auto* clusterGroup = app.add_option_group("Cluster", "render the previews on tessera-node processes");
  clusterGroup->add_option("--cluster", o.cluster.sequence.cluster, "cluster config (configs/*.json)")
      ->check(CLI::ExistingFile);
  clusterGroup->add_option("--nodes", o.cluster.sequence.nodes, "HOST:PORT,... replacing the config's node addresses");
  clusterGroup->add_option("--node-token-file", o.cluster.sequence.tokenFile, "the nodes' shared token")
      ->check(CLI::ExistingFile);
}

// What one client may hold, and how long the service waits.
void addLimitOptions(CLI::App& app, CullOptions& o) {
  auto* limitGroup = app.add_option_group("Limits", "what one client may hold, and how long the service waits");
  limitGroup->add_option("--io-threads", o.service.ioThreads, "threads serving the connections")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  limitGroup->add_option("--max-connections", o.service.maxConnections, "connections open at once, from everyone")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  limitGroup
      ->add_option("--max-connections-per-address", o.service.connectionsPerAddress,
                   "connections open at once from one client address (more: 429)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  limitGroup
      ->add_option("--max-requests-per-address", o.service.requestsPerAddress,
                   "/v1/cull requests waiting or ranked at once for one client address (more: 429)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  limitGroup
      ->add_option("--max-previews-per-address", o.service.previewsPerAddress,
                   "/v1/preview streams at once from one client address (more: 429)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  limitGroup->add_option("--cull-queue", o.service.cullQueue, "/v1/cull requests waiting, from everyone (more: 503)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  limitGroup
      ->add_option("--header-timeout", o.headerTimeout, "seconds a new connection has for its request line and headers")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  limitGroup
      ->add_option("--keepalive-timeout", o.keepAliveTimeout,
                   "seconds an idle keep-alive connection has for its next request's headers")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  limitGroup
      ->add_option("--transfer-timeout", o.transferTimeout,
                   "seconds a request body or a response has, plus its size at --min-rate")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  limitGroup->add_option("--min-rate", o.service.minRate, "bytes per second a body or a response must at least move")
      ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 40))
      ->capture_default_str();
  limitGroup
      ->add_option("--ping-timeout", o.pingTimeout,
                   "seconds a /v1/preview WebSocket may leave a ping unanswered (pinged at half of it)")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
}

// False when the command line only asked for help.
bool parseOptions(int argc, char** argv, CullOptions& o) {
  CLI::App app{"Rank a scene's objects by visible coverage for a browser's view, and serve them one by one"};
  addServiceOptions(app, o);
  addLimitOptions(app, o);
  o.limits.add(app, o.import);
  if (!tsr::app::parseCommandLine(app, argc, argv)) return false;
  o.limits.apply(o.import);
  o.service.headerTimeout = tsr::app::ServiceLimits::Seconds(o.headerTimeout);
  o.service.keepAliveTimeout = tsr::app::ServiceLimits::Seconds(o.keepAliveTimeout);
  o.service.transferTimeout = tsr::app::ServiceLimits::Seconds(o.transferTimeout);
  o.service.pingTimeout = tsr::app::ServiceLimits::Seconds(o.pingTimeout);
  return true;
}

int run(int argc, char** argv) {
  CullOptions o;
  if (!parseOptions(argc, argv, o)) return 0;

  spdlog::set_default_logger(spdlog::stderr_color_mt("cull"));
  fitOpenFiles(o.service);
  const std::string token = o.tokenFile.empty() ? "" : tsr::cluster::readTokenFile(o.tokenFile);
  const tsr::cluster::NodeAddress address =
      tsr::cluster::parseNodeAddress(o.listen.find(':') == std::string::npos ? o.listen + ":0" : o.listen);
  boost::asio::io_context io(o.service.ioThreads);
  boost::asio::ip::tcp::resolver resolver(io);
  const auto endpoint = resolver.resolve(address.host, std::to_string(address.port))->endpoint();
  if (token.empty() && !endpoint.address().is_loopback())
    throw std::invalid_argument("refusing to listen on " + address.host + " (" + endpoint.address().to_string() +
                                ") without --token-file: anyone who reaches it could use the service");

  tsr::med::Parameters parameters;
  if (o.threads) parameters.set("threads", o.threads);
  if (o.cluster.sequence.cluster.empty() &&
      (!o.cluster.sequence.nodes.empty() || !o.cluster.sequence.tokenFile.empty()))
    throw std::invalid_argument("--nodes and --node-token-file go with --cluster CONFIG");
  tsr::app::CullService cull(o.scene, o.import, o.backend, parameters);
  tsr::app::PreviewOptions preview;
  preview.maxStreams = o.previews;
  preview.sampleLimit = o.previewSpp;
  preview.handshakeTimeout = o.service.headerTimeout;
  preview.pingTimeout = o.service.pingTimeout;
  if (o.previews > 0)
    preview.open = tsr::app::previewViewports(cull, o.previewBackend, parameters, o.cluster, preview.maxStreams);
  tsr::app::PreviewStreams streams(cull, std::move(preview));
  const tsr::app::WebFiles webFiles(o.web);
  if (const std::string why = webFiles.missing(); !why.empty()) spdlog::warn("GET / will not work: {}", why);

  boost::asio::ip::tcp::acceptor acceptor(io, endpoint);
  std::cout << "listening on " << address.host << ":" << acceptor.local_endpoint().port() << std::endl;
  std::cerr << o.scene << ": " << cull.totalObjects() << " objects" << std::endl;
  tsr::app::HttpService http(cull, streams, webFiles, {token, o.maxObjects, o.service});
  http.serve(acceptor);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return tsr::app::runProgram(run, argc, argv); }
