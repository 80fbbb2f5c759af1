#pragma once
// Boost 1.74's awaitable.hpp uses std::exchange without including <utility>.
#include <utility>

#include <boost/asio.hpp>

namespace tsr::cluster {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;
}  // namespace tsr::cluster
