// Boost.Asio's io_context by name only: a header that keeps a reference to one includes this, and
// only the translation units that do I/O parse Boost.Asio itself (openlcb/asio.hpp: about 1,800
// headers, seconds of every compile and every clang-tidy run that includes it).
#pragma once

namespace boost::asio {
class io_context;  // NOLINT(readability-identifier-naming): Boost.Asio's name
}  // namespace boost::asio
