// The one place Boost.Asio is included: Boost 1.74's Asio uses std::exchange without including
// <utility>, which g++ 12 in C++20 mode no longer pulls in transitively.
#pragma once

#include <utility>

#include <boost/asio.hpp>
