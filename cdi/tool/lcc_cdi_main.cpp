// lcc-cdi: validate, lay out and render CDI files (and FDI files, a train node's functions).
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "cdi/tool/commands.hpp"
#include "olcb_version.hpp"

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage =
    "usage: lcc-cdi COMMAND [OPTIONS] FILE...\n"
    "\n"
    "Commands:\n"
    "  validate FILE...      check each CDI against its schema and the standard's rules\n"
    "  layout FILE [--json]  list every variable with its space, address and size\n"
    "  render FILE           print the CDI as an indented, human-readable tree\n"
    "  render --html FILE    print it as one HTML page, as a configuration tool shows it\n"
    "\n"
    "A FILE whose root element is <fdi> is an FDI (Function Description Information, a train\n"
    "node's space 0xFA): validate judges it by the FDI standard, layout lists its functions,\n"
    "render prints the function list.\n"
    "A FILE over 16 MiB (the CDI limit) is refused unread; a FIFO or device is read no further.\n"
    "Run 'lcc-cdi COMMAND --help' for the options of a command.\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << kUsage;
        return olcb::cdi::tool::kExitUsage;
    }
    const std::string command = argv[1];
    if (command == "--help" || command == "-h" || command == "help") {
        std::cout << kUsage;
        return 0;
    }
    if (command == "--version") {
        std::cout << "lcc-cdi " << olcb::kVersion << "\n";
        return 0;
    }
    std::vector<std::string> args(argv + 2, argv + argc);
    try {
        if (command == "validate") return olcb::cdi::tool::run_validate(args);
        if (command == "layout") return olcb::cdi::tool::run_layout(args);
        if (command == "render") return olcb::cdi::tool::run_render(args);
    } catch (const po::error& e) {
        std::cerr << "lcc-cdi " << command << ": " << e.what() << "\n";
        return olcb::cdi::tool::kExitUsage;
    } catch (const std::exception& e) {
        std::cerr << "lcc-cdi " << command << ": " << e.what() << "\n";
        return olcb::cdi::tool::kExitUsage;
    }
    std::cerr << "lcc-cdi: unknown command '" << command << "'\n\n" << kUsage;
    return olcb::cdi::tool::kExitUsage;
}
