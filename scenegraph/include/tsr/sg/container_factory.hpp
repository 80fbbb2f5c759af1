#pragma once
// Makes an empty container of a type known only at run time (replicas,
// decoders), and answers questions about a type's fields.
#include <memory>

#include "tsr/sg/container.hpp"

namespace tsr::sg {

std::unique_ptr<Container> makeContainer(ContainerType type);
// A default-valued instance, for reflection only.
const Container& prototype(ContainerType type);

}  // namespace tsr::sg
