// Misbehaviour is a layer: the protocol libraries (openlcb/, memory/) know no fault. A fault lives
// in simnode and reaches them only through their hooks (NodeStack's frame and message filters,
// the stream window policy, the memory server's typed decisions), so neither its name nor the
// identifier made of it may appear in their sources.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "simnode/faults.hpp"

namespace olcb::simnode {
namespace {

namespace fs = std::filesystem;

std::string whole_word(const std::string& form) {
    static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
    return "(^|[^A-Za-z0-9_-])" + std::regex_replace(form, special, R"(\$&)") +
           "($|[^A-Za-z0-9_-])";
}

TEST(FaultLayerTest, NoFaultNameAppearsInTheProtocolLibraries) {
    // Forms that are the standards' own words, which the libraries must use: the fault
    // reply-pending is named after the Datagram Received OK's Reply Pending flag
    // (DatagramTransportS §4.2), the libraries' reply_pending.
    const std::set<std::string> protocol_terms = {"reply_pending"};
    std::vector<std::pair<std::string, std::regex>> patterns;
    for (const std::string& name : fault_names()) {
        std::string identifier = name;
        std::replace(identifier.begin(), identifier.end(), '-', '_');
        for (const std::string& form : {name, identifier}) {
            if (protocol_terms.contains(form)) continue;
            patterns.emplace_back(form, std::regex(whole_word(form), std::regex::icase));
        }
    }
    ASSERT_GT(patterns.size(), 60u);
    std::size_t files = 0;
    for (const char* dir : {"openlcb", "memory"}) {
        for (const auto& e : fs::recursive_directory_iterator(fs::path(OLCB_SOURCE_DIR) / dir)) {
            const std::string ext = e.path().extension().string();
            if (!e.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
            ++files;
            std::ifstream in(e.path());
            std::size_t number = 0;
            for (std::string line; std::getline(in, line);) {
                ++number;
                for (const auto& [form, pattern] : patterns) {
                    EXPECT_FALSE(std::regex_search(line, pattern))
                        << e.path().string() << ":" << number << " names the fault '" << form
                        << "': " << line;
                }
            }
        }
    }
    EXPECT_GT(files, 40u);
}

}  // namespace
}  // namespace olcb::simnode
