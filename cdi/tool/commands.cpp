#include "cdi/tool/commands.hpp"

#include <algorithm>
#include <charconv>
#include <iostream>
#include <memory>
#include <sstream>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "base/utf8.hpp"
#include "cdi/cdi_file.hpp"
#include "cdi/fdi_parser.hpp"
#include "cdi/fdi_render.hpp"
#include "cdi/html_page.hpp"
#include "cdi/layout.hpp"
#include "cdi/parser.hpp"
#include "cdi/render.hpp"
#include "cdi/render_html.hpp"
#include "cdi/rule_finding.hpp"
#include "cdi/string_codec.hpp"
#include "cdi/validator.hpp"
#include "cdi/variable_name.hpp"

namespace olcb::cdi::tool {

namespace po = boost::program_options;

namespace {

// Parses `args` with `options` plus positional FILEs; prints help and returns true on --help.
bool parse_args(const std::vector<std::string>& args, po::options_description& options,
                const char* synopsis, po::variables_map& vm) {
    options.add_options()("help,h", "show this help")("file", po::value<std::vector<std::string>>(),
                                                      "CDI or FDI file");
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

// A CDI's bytes as a terminal line shows them: invalid UTF-8 as U+FFFD, control characters (a
// name's newline or tab would break a line or a column, a C1 CSI would drive the terminal) as '?'.
std::string display(std::string_view text) {
    return base::printable(text);
}

// A CDI parsed and laid out. The document is on the heap because the layout points into it.
struct Loaded {
    std::unique_ptr<Document> document;
    Layout layout;
};

// A file's bytes for layout and render (nullopt after printing why on stderr), with a warning
// when they are not UTF-8.
std::optional<std::string> read_input(const std::string& path) {
    std::string error;
    auto bytes = read_cdi_file(path, error);
    if (!bytes) {
        std::cerr << "error: " << display(error) << "\n";
        return std::nullopt;
    }
    if (const auto bad = base::find_invalid_utf8(*bytes)) {
        const std::string_view before = std::string_view(*bytes).substr(0, *bad);
        const auto line = 1 + std::count(before.begin(), before.end(), '\n');
        std::cerr << display(path) << ":" << line << ": warning: invalid UTF-8 at offset " << *bad
                  << " (see lcc-cdi validate)\n";
    }
    return bytes;
}

// Reads, parses and lays out one CDI; prints every finding to stderr and returns nullopt on
// errors.
std::optional<Loaded> load(const std::string& path, std::optional<std::string> bytes) {
    if (!bytes) return std::nullopt;
    ParseResult parsed = parse(*bytes);
    // The model owns copies of all it needs: the text (up to 16 MiB) need not live on through
    // the layout and the output, where the peak of a large CDI is.
    bytes.reset();
    if (!parsed.document) {
        for (const auto& d : parsed.diagnostics)
            std::cerr << display(format_diagnostic(path, d)) << "\n";
        return std::nullopt;
    }
    auto document = std::make_unique<Document>(std::move(*parsed.document));
    LayoutResult result = build_layout(*document);
    for (const auto& d : result.diagnostics)
        std::cerr << display(format_diagnostic(path, d)) << "\n";
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

// One finding the way lcc-conform's text report shows the check: "FILE:LINE: FAIL id: message",
// expected and seen under it; cdi.valid's diagnostics follow as FILE:LINE: error|warning lines.
void print_finding(const std::string& path, const RuleFinding& f) {
    std::cout << display(path);
    if (f.line != 0) std::cout << ":" << f.line;
    std::cout << ": " << rule_status_name(f.status) << " " << f.check_id << ": "
              << display(f.message) << "\n";
    if (!f.expected.empty()) std::cout << "      expected: " << display(f.expected) << "\n";
    if (!f.seen.empty()) std::cout << "      seen:     " << display(f.seen) << "\n";
    if (!f.clause.empty() && (f.status == RuleStatus::kFail || f.status == RuleStatus::kWarn))
        std::cout << "      clause:   " << display(f.clause) << "\n";
    for (const auto& d : f.diagnostics) std::cout << display(format_diagnostic(path, d)) << "\n";
}

int run_validate(const std::vector<std::string>& args) {
    po::options_description options("lcc-cdi validate options");
    options.add_options()("quiet,q", "print only FAIL and WARN findings, no 'ok' lines");
    po::variables_map vm;
    if (parse_args(args, options,
                   "lcc-cdi validate [--quiet] FILE...\n\nEach FILE is a CDI, or an FDI when its "
                   "root element is <fdi>.",
                   vm))
        return kExitOk;
    const auto files = files_of(vm);
    if (files.empty()) throw po::error("no FILE given");
    int status = kExitOk;
    for (const auto& path : files) {
        std::string error;
        auto bytes = read_cdi_file(path, error);
        if (!bytes) {
            std::cout << "error: " << display(error) << "\n";
            status = kExitErrors;
            continue;
        }
        bool failed = false;
        // The root element tells an FDI (a train node's space 0xFA) from a CDI.
        const auto findings = is_fdi_text(*bytes) ? check_fdi_rules(*bytes) : check_rules(*bytes);
        for (const RuleFinding& f : findings) {
            if (f.status != RuleStatus::kFail && f.status != RuleStatus::kWarn) continue;
            print_finding(path, f);
            failed = failed || f.status == RuleStatus::kFail;
        }
        if (failed) {
            status = kExitErrors;
        } else if (vm.count("quiet") == 0) {
            std::cout << display(path) << ": ok\n";
        }
    }
    return status;
}

namespace {

// The variable's type as lcc-cdi names it (the tag of an unknown element).
std::string type_name(const Element& e) {
    return e.kind == ElementKind::kUnknown ? e.tag : kind_name(e.kind);
}

// One variable of `layout --json`. The name is the JMRI backup key (cdi/variable_name.hpp); the
// replicas' CDI names (repname) follow only when the CDI gives some, as the label a
// configuration tool shows.
void print_layout_json(std::ostream& out, const Layout& layout, const Cursor& c, bool first) {
    const Element& e = c.element();
    nlohmann::json v = {{"name", variable_name(layout, c)},
                        {"type", type_name(e)},
                        {"space", c.space()},
                        {"address", c.address()},
                        {"size", c.size()}};
    if (std::string replicas = replica_names(c); !replicas.empty()) v["replica"] = replicas;
    add_details(e, v);
    // The CDI's names are untrusted bytes: invalid UTF-8 becomes U+FFFD, never an exception
    // half-way through the array.
    out << (first ? "\n" : ",\n")
        << v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// One variable of `layout`, a tab-separated line (the same fields as the JSON).
void print_layout_text(std::ostream& out, const Layout& layout, const Cursor& c) {
    const Element& e = c.element();
    out << display(variable_name(layout, c)) << "\t" << display(type_name(e)) << "\tspace "
        << c.space() << "\taddress " << c.address() << "\tsize " << c.size();
    if (std::string replicas = replica_names(c); !replicas.empty())
        out << "\treplica " << display(replicas);
    std::string details = details_text(e);
    if (!details.empty()) out << "\t" << display(details);
    out << "\n";
}

// An FDI's model; prints the parser's findings to stderr and returns nullopt on errors (a
// function left out would make the list wrong).
std::optional<FdiDocument> load_fdi(const std::string& path, const std::string& bytes) {
    FdiParseResult parsed = parse_fdi(bytes);
    for (const auto& d : parsed.diagnostics)
        std::cerr << display(format_diagnostic(path, d)) << "\n";
    if (!parsed.document || has_errors(parsed.diagnostics)) return std::nullopt;
    return std::move(parsed.document);
}

// The name `layout` gives a function: its own, or F<number> when it has none.
std::string fdi_variable_name(const FdiFunction& f) {
    return f.name.empty() ? "F" + std::to_string(f.number) : f.name;
}

// One function of an FDI's `layout --json`.
nlohmann::json fdi_variable_json(const FdiFunction& f) {
    nlohmann::json v = {{"name", fdi_variable_name(f)},
                        {"type", function_kind_name(f.kind)},
                        {"space", 249},
                        {"address", f.number},
                        {"size", 1}};
    if (f.kind == FunctionKind::kAnalog) {
        v["min"] = f.value_min();
        v["max"] = f.value_max();
    }
    if (f.icon) v["icon"] = *f.icon;
    return v;
}

// One function of an FDI's `layout`, a tab-separated line (the same fields as the JSON).
std::string fdi_variable_line(const FdiFunction& f) {
    std::string line = display(fdi_variable_name(f)) + "\t" +
                       std::string(function_kind_name(f.kind)) + "\tspace 249\taddress " +
                       std::to_string(f.number) + "\tsize 1";
    std::string details;
    if (f.kind == FunctionKind::kAnalog) {
        details = "min=" + std::to_string(f.value_min()) + " max=" + std::to_string(f.value_max());
    }
    if (f.icon) details += (details.empty() ? "" : " ") + ("icon=" + std::to_string(*f.icon));
    return details.empty() ? line : line + "\t" + details;
}

// An FDI's function space 0xF9 as `layout` lists it: one byte per function at its number
// (FunctionDescriptionInformationTN §3.1), in document order.
void print_fdi_layout(std::ostream& out, const FdiDocument& doc, bool json) {
    if (json) out << "{\"variables\":[";
    bool first = true;
    for (const FdiFunction& f : doc.functions) {
        if (json) {
            out << (first ? "\n" : ",\n")
                << fdi_variable_json(f).dump(-1, ' ', false,
                                             nlohmann::json::error_handler_t::replace);
        } else {
            out << fdi_variable_line(f) << "\n";
        }
        first = false;
    }
    if (json) out << (first ? "" : "\n") << "]}\n";
}

}  // namespace

int run_layout(const std::vector<std::string>& args) {
    po::options_description options("lcc-cdi layout options");
    options.add_options()("json",
                          "print JSON: {\"variables\":[{\"name\",\"type\",\"space\","
                          "\"address\",\"size\",...}]}");
    po::variables_map vm;
    if (parse_args(args, options,
                   "lcc-cdi layout [--json] FILE\n\nAn FDI lists its functions as the bytes of "
                   "space 249 (0xF9) they address.",
                   vm))
        return kExitOk;
    const auto files = files_of(vm);
    if (files.size() != 1) throw po::error("layout takes exactly one FILE");
    auto bytes = read_input(files.front());
    const bool json = vm.count("json") != 0;
    if (bytes && is_fdi_text(*bytes)) {
        const auto fdi = load_fdi(files.front(), *bytes);
        if (!fdi) return kExitErrors;
        print_fdi_layout(std::cout, *fdi, json);
        return kExitOk;
    }
    auto loaded = load(files.front(), std::move(bytes));
    if (!loaded) return kExitErrors;
    std::ostream& out = std::cout;
    // Streamed one variable at a time: a 10^6-replication CDI never builds a whole JSON tree.
    if (json) out << "{\"variables\":[";
    bool first = true;
    loaded->layout.visit([&](const Cursor& c) {
        if (json) {
            print_layout_json(out, loaded->layout, c, first);
        } else {
            print_layout_text(out, loaded->layout, c);
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
    if (parse_args(args, options,
                   "lcc-cdi render [--html] FILE\n\nAn FDI renders as its function list (text "
                   "only).",
                   vm))
        return kExitOk;
    const auto files = files_of(vm);
    if (files.size() != 1) throw po::error("render takes exactly one FILE");
    auto bytes = read_input(files.front());
    if (bytes && is_fdi_text(*bytes)) {
        if (vm.count("html") != 0) throw po::error("--html renders a CDI; an FDI renders as text");
        const auto fdi = load_fdi(files.front(), *bytes);
        if (!fdi) return kExitErrors;
        render_fdi(*fdi, std::cout);
        return kExitOk;
    }
    auto loaded = load(files.front(), std::move(bytes));
    if (!loaded) return kExitErrors;
    if (vm.count("html") != 0) {
        // The page is written from the layout element by element; the model goes before output.
        const std::string page = render_html(loaded->layout, files.front());
        loaded.reset();
        std::cout << page;
    } else {
        render(loaded->layout, std::cout);
    }
    return kExitOk;
}

}  // namespace olcb::cdi::tool
