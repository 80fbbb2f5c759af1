#include "tsr/cov/id_buffer.hpp"

namespace tsr::cov {

IdBuffer::IdBuffer(const Region& r)
    : region(r),
      ids(static_cast<std::size_t>(r.pixelCount()), kBackground),
      depth(static_cast<std::size_t>(r.pixelCount()), kNoDepth) {}

}  // namespace tsr::cov
