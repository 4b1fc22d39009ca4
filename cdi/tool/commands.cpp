#include "cdi/tool/commands.hpp"

#include <charconv>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"
#include "cdi/render.hpp"
#include "cdi/render_html.hpp"
#include "cdi/validator.hpp"

namespace olcb::cdi::tool {

namespace po = boost::program_options;

namespace {

// Parses `args` with `options` plus positional FILEs; prints help and returns true on --help.
bool parse_args(const std::vector<std::string>& args, po::options_description& options,
                const char* synopsis, po::variables_map& vm) {
    options.add_options()("help,h", "show this help")("file", po::value<std::vector<std::string>>(),
                                                      "CDI file");
    po::positional_options_description positional;
    positional.add("file", -1);
    po::store(po::command_line_parser(args).options(options).positional(positional).run(), vm);
    po::notify(vm);
    if (vm.count("help") != 0) {
        std::cout << "usage: " << synopsis << "\n\n" << options;
        return true;
    }
    return false;
}

std::vector<std::string> files_of(const po::variables_map& vm) {
    return vm.count("file") != 0 ? vm["file"].as<std::vector<std::string>>()
                                 : std::vector<std::string>{};
}

// Reads, parses and lays out one CDI; prints every finding to stderr and returns nullopt on
// errors. The document is on the heap because the layout points into it.
struct Loaded {
    std::unique_ptr<Document> document;
    Layout layout;
};

std::optional<Loaded> load(const std::string& path) {
    std::string error;
    auto bytes = read_file(path, error);
    if (!bytes) {
        std::cerr << path << ": error: " << error << "\n";
        return std::nullopt;
    }
    ParseResult parsed = parse(*bytes);
    if (!parsed.document) {
        for (const auto& d : parsed.diagnostics) std::cerr << format_diagnostic(path, d) << "\n";
        return std::nullopt;
    }
    auto document = std::make_unique<Document>(std::move(*parsed.document));
    LayoutResult result = build_layout(*document);
    for (const auto& d : result.diagnostics) std::cerr << format_diagnostic(path, d) << "\n";
    if (!result.layout) return std::nullopt;
    return Loaded{std::move(document), std::move(*result.layout)};
}

nlohmann::json int_json(WideInt v) {
    if (v >= 0 && v <= static_cast<WideInt>(UINT64_MAX)) return static_cast<std::uint64_t>(v);
    if (v < 0 && v >= static_cast<WideInt>(INT64_MIN)) return static_cast<std::int64_t>(v);
    return to_string(v);
}

// The type-specific details of a variable for `layout --json`.
void add_details(const Element& e, nlohmann::json& out) {
    if (e.int_min) out["min"] = int_json(*e.int_min);
    if (e.int_max) out["max"] = int_json(*e.int_max);
    if (e.int_default) out["default"] = int_json(*e.int_default);
    if (e.float_min) out["min"] = *e.float_min;
    if (e.float_max) out["max"] = *e.float_max;
    if (e.float_default) out["default"] = *e.float_default;
    if (e.text_default) out["default"] = *e.text_default;
    if (e.action_value) out["value"] = int_json(*e.action_value);
    if (e.kind == ElementKind::kInt) out["signed"] = e.is_signed();
    if (e.formatting) out["formatting"] = *e.formatting;
    if (e.blob_mode) out["mode"] = *e.blob_mode;
    if (e.map) {
        nlohmann::json map = nlohmann::json::array();
        for (const auto& entry : e.map->entries) {
            map.push_back({{"property", entry.property}, {"value", entry.value}});
        }
        out["map"] = std::move(map);
    }
}

// One-line summary of the details for the text form of `layout`.
std::string details_text(const Element& e) {
    std::string out;
    auto add = [&out](const std::string& s) { out += (out.empty() ? "" : " ") + s; };
    if (e.kind == ElementKind::kInt && e.is_signed()) add("signed");
    if (e.int_min) add("min=" + to_string(*e.int_min));
    if (e.int_max) add("max=" + to_string(*e.int_max));
    if (e.int_default) add("default=" + to_string(*e.int_default));
    auto real = [](double v) {
        char buf[32];
        auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
        return ec == std::errc() ? std::string(buf, end) : std::string("?");
    };
    if (e.float_min) add("min=" + real(*e.float_min));
    if (e.float_max) add("max=" + real(*e.float_max));
    if (e.float_default) add("default=" + real(*e.float_default));
    if (e.text_default) add("default=\"" + *e.text_default + "\"");
    if (e.action_value) add("value=" + to_string(*e.action_value));
    if (e.map) {
        std::string map = "map={";
        for (std::size_t i = 0; i < e.map->entries.size(); ++i) {
            if (i != 0) map += ", ";
            map += e.map->entries[i].property + ": " + e.map->entries[i].value;
        }
        add(map + "}");
    }
    return out;
}

}  // namespace

std::optional<std::string> read_file(const std::string& path, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open file";
        return std::nullopt;
    }
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) {
        error = "read error";
        return std::nullopt;
    }
    return std::move(buffer).str();
}

int run_validate(const std::vector<std::string>& args) {
    po::options_description options("lcc-cdi validate options");
    options.add_options()("quiet,q", "print only errors and warnings, no 'ok' lines");
    po::variables_map vm;
    if (parse_args(args, options, "lcc-cdi validate [--quiet] FILE...", vm)) return kExitOk;
    const auto files = files_of(vm);
    if (files.empty()) throw po::error("no FILE given");
    int status = kExitOk;
    for (const auto& path : files) {
        std::string error;
        auto bytes = read_file(path, error);
        if (!bytes) {
            std::cout << path << ": error: " << error << "\n";
            status = kExitErrors;
            continue;
        }
        ValidationReport report = validate(*bytes);
        for (const auto& d : report.diagnostics) std::cout << format_diagnostic(path, d) << "\n";
        if (!report.ok()) {
            status = kExitErrors;
        } else if (vm.count("quiet") == 0) {
            std::cout << path << ": ok\n";
        }
    }
    return status;
}

int run_layout(const std::vector<std::string>& args) {
    po::options_description options("lcc-cdi layout options");
    options.add_options()("json",
                          "print JSON: {\"variables\":[{\"path\",\"type\",\"space\","
                          "\"address\",\"size\",...}]}");
    po::variables_map vm;
    if (parse_args(args, options, "lcc-cdi layout [--json] FILE", vm)) return kExitOk;
    const auto files = files_of(vm);
    if (files.size() != 1) throw po::error("layout takes exactly one FILE");
    auto loaded = load(files.front());
    if (!loaded) return kExitErrors;
    const bool json = vm.count("json") != 0;
    std::ostream& out = std::cout;
    // Streamed one variable at a time: a 10^6-replication CDI never builds a whole JSON tree.
    if (json) out << "{\"variables\":[";
    bool first = true;
    loaded->layout.visit([&](const Cursor& c) {
        const Element& e = c.element();
        if (json) {
            nlohmann::json v = {
                {"path", c.path()},
                {"type", e.kind == ElementKind::kUnknown ? e.tag : kind_name(e.kind)},
                {"space", c.space()},
                {"address", c.address()},
                {"size", c.size()}};
            add_details(e, v);
            out << (first ? "\n" : ",\n") << v.dump();
        } else {
            out << c.path() << "\t" << (e.kind == ElementKind::kUnknown ? e.tag : kind_name(e.kind))
                << "\tspace " << c.space() << "\taddress " << c.address() << "\tsize " << c.size();
            std::string details = details_text(e);
            if (!details.empty()) out << "\t" << details;
            out << "\n";
        }
        first = false;
    });
    if (json) out << (first ? "" : "\n") << "]}\n";
    return kExitOk;
}

int run_render(const std::vector<std::string>& args) {
    po::options_description options("lcc-cdi render options");
    options.add_options()("html",
                          "print one self-contained HTML page instead: segments as tabs, groups, "
                          "replications, hints, and each space's memory map");
    po::variables_map vm;
    if (parse_args(args, options, "lcc-cdi render [--html] FILE", vm)) return kExitOk;
    const auto files = files_of(vm);
    if (files.size() != 1) throw po::error("render takes exactly one FILE");
    auto loaded = load(files.front());
    if (!loaded) return kExitErrors;
    if (vm.count("html") != 0) {
        std::cout << render_html(loaded->layout, files.front());
    } else {
        render(loaded->layout, std::cout);
    }
    return kExitOk;
}

}  // namespace olcb::cdi::tool
