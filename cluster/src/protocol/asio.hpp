#pragma once
// Boost 1.74's awaitable.hpp uses std::exchange without including <utility>.
#include <utility>

// Asio 1.74 looks for co_await support in clang only through
// <experimental/coroutine>, which libstdc++ lacks; clang 14 has C++20's. Set
// here, not by the build, so clang-tidy over gcc's compile commands and the
// clang fuzz build parse the coroutines alike.
#if defined(__clang__) && !defined(BOOST_ASIO_HAS_CO_AWAIT)
#define BOOST_ASIO_HAS_CO_AWAIT 1
#endif
#include <boost/asio.hpp>

namespace tsr::cluster {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;
}  // namespace tsr::cluster
