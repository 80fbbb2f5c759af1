// tessera-node --listen HOST:PORT [--token-file F | --insecure] [--name N] [--threads N]
//              [--present none|window|files:DIR]
// Serves render requests of Tessera clients. The first line on stdout is
// "listening on HOST:PORT" (port 0 picks a free one), for scripts and tests.
// Without a token file it listens only on loopback, unless --insecure.
// Start-up errors: one "error:" line on stderr, exit status 2.
#include <atomic>
#include <filesystem>
#include <iostream>
#include <thread>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "backends.hpp"
#include "command_line.hpp"
#include "error_line.hpp"
#include "tsr/cluster/auth.hpp"
#include "tsr/cluster/node_server.hpp"
#ifdef TSR_HAVE_WINDOW
#include "window_presenter.hpp"
#endif

int main(int argc, char** argv) {
  CLI::App app{"Tessera render node"};
  std::string listen = "127.0.0.1:0", tokenFile, name = "node", logLevel = "info";
  unsigned threads = 0;
  app.add_option("--listen", listen, "HOST:PORT to listen on (port 0: a free port)");
  app.add_option("--token-file", tokenFile,
                 "file holding the shared token clients must prove (required to listen beyond loopback)")
      ->check(tsr::app::FileName());
  bool insecure = false;
  app.add_flag("--insecure", insecure,
               "without --token-file, listen on a non-loopback address anyway: anyone may connect");
  app.add_option("--name", name, "name reported to clients");
  app.add_option("--threads", threads, "render threads per viewport (0: all cores)");
  std::string present = "none";
  app.add_option("--present", present,
                 "what to do with the wall tile when the swap barrier releases its frame: none, window (a window "
                 "placed as the client's config says), files:DIR (DIR/NAME-frameN-X-Y.exr, for headless walls)")
      ->capture_default_str();
  app.add_option("--log-level", logLevel, "trace, debug, info, warn, error");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::ParseError& e) {  // CLI11's own exit would print several lines and exit 105 and up
    tsr::app::printError(e.what());
    return 2;
  }

  try {
    // Logs go to stderr: stdout carries only the "listening on" line.
    spdlog::set_default_logger(spdlog::stderr_color_mt("node"));
    spdlog::set_level(spdlog::level::from_str(logLevel));
    spdlog::set_pattern("[node " + name + "] [%l] %v");
    tsr::cluster::NodeOptions options;
    options.listen = tsr::cluster::parseNodeAddress(listen.find(':') == std::string::npos ? listen + ":0" : listen);
    options.name = name;
    options.threads = threads;
#ifdef TSR_HAVE_WINDOW
    std::shared_ptr<tsr::app::WindowPresenter> window;
#endif
    if (present.rfind("files:", 0) == 0) {
      std::string dir = present.substr(6);
      if (dir.empty() || !std::filesystem::is_directory(dir))
        throw std::invalid_argument("--present files:DIR needs an existing directory, not '" + dir + "'");
      options.presenter = tsr::cluster::makeFilePresenter(dir, name);
    } else if (present == "window") {
#ifdef TSR_HAVE_WINDOW
      window = std::make_shared<tsr::app::WindowPresenter>("tessera-node " + name);
      options.presenter = window;
#else
      throw std::invalid_argument("--present window: this build has no Vulkan window support");
#endif
    } else if (present != "none") {
      throw std::invalid_argument("--present must be none, window or files:DIR, not '" + present + "'");
    }
    if (!tokenFile.empty()) options.token = tsr::cluster::readTokenFile(tokenFile);
    options.insecure = insecure;

    tsr::med::ViewportRegistry registry;
    tsr::app::registerBackends(registry);
    if (registry.backends().empty()) spdlog::warn("this build registers no back-end; render requests will fail");

    tsr::cluster::NodeServer server(options, registry);
    server.stopOnSignals();
    auto bound = server.listen();
    std::cout << "listening on " << bound.text() << std::endl;  // endl: scripts read this line at once
#ifdef TSR_HAVE_WINDOW
    if (window) {
      // GLFW on this (the main) thread, the server beside it; either ending stops the other.
      std::atomic<bool> stopped{false};
      std::thread serving([&] {
        server.run();
        stopped = true;
      });
      try {
        if (window->run(stopped)) spdlog::info("window closed: stopping");
      } catch (...) {
        server.stop();
        serving.join();
        throw;
      }
      server.stop();
      serving.join();
      return 0;
    }
#endif
    server.run();
    return 0;
  } catch (const std::exception& e) {
    tsr::app::printError(e.what());
    return 2;
  }
}
