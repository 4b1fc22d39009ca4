#include "cdi/fdi_render.hpp"

#include <string_view>

#include "base/utf8.hpp"

namespace olcb::cdi {
namespace {

std::string indent(std::size_t depth) {
    return std::string(depth * 2, ' ');
}

std::string label(const std::string& name) {
    return name.empty() ? "(unnamed)" : "\"" + base::printable(name) + "\"";
}

// "F3 momentary \"Horn\"", with an analog function's range and an icon when given.
std::string function_line(const FdiFunction& f) {
    std::string line =
        "F" + std::to_string(f.number) + " " + std::string(function_kind_name(f.kind));
    if (f.kind == FunctionKind::kAnalog)
        line += " " + std::to_string(f.value_min()) + ".." + std::to_string(f.value_max());
    line += " " + label(f.name);
    if (f.icon) line += " icon " + std::to_string(*f.icon);
    return line;
}

// Text for element content: printable (no control character, valid UTF-8), markup escaped.
std::string escaped(std::string_view text) {
    std::string out;
    for (const char c : base::printable(text)) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

void text_element(std::string& out, std::size_t depth, std::string_view tag,
                  const std::string& text) {
    if (text.empty()) return;
    out += indent(depth) + "<" + std::string(tag) + ">" + escaped(text) + "</" + std::string(tag) +
           ">\n";
}

void write_function(std::string& out, std::size_t depth, const FdiFunction& f) {
    out += indent(depth) + "<function kind=\"" + std::string(function_kind_name(f.kind)) + "\"" +
           (f.size_given ? " size=\"1\"" : "") + ">\n";
    text_element(out, depth + 1, "name", f.name);
    if (f.icon) text_element(out, depth + 1, "icon", std::to_string(*f.icon));
    text_element(out, depth + 1, "number", std::to_string(f.number));
    if (f.min) text_element(out, depth + 1, "min", std::to_string(*f.min));
    if (f.max) text_element(out, depth + 1, "max", std::to_string(*f.max));
    out += indent(depth) + "</function>\n";
}

}  // namespace

void render_fdi(const FdiDocument& doc, std::ostream& out) {
    out << "Segment " << label(doc.name) << ", space 249 (functions)\n";
    if (!doc.description.empty()) out << "  | " << base::printable(doc.description) << "\n";
    doc.walk([&](const FdiStep& step) {
        const std::string at = indent(step.depth + 1);
        if (step.kind == FdiStep::Kind::kFunction) {
            out << at << function_line(doc.functions[step.index]) << "\n";
        } else if (step.kind == FdiStep::Kind::kOpenGroup) {
            const FdiGroup& g = doc.groups[step.index];
            out << at << "group " << label(g.name) << "\n";
            if (!g.description.empty())
                out << at << "  | " << base::printable(g.description) << "\n";
        }
    });
}

std::string write_fdi(const FdiDocument& doc) {
    std::string out =
        "<?xml version=\"1.0\"?>\n"
        "<fdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
        "xsi:noNamespaceSchemaLocation=\"https://openlcb.org/schema/fdi/1/1/fdi.xsd\">\n";
    out += std::string("<segment") + (doc.space_given ? " space=\"249\"" : "") +
           (doc.origin_given ? " origin=\"0\"" : "") + ">\n";
    text_element(out, 1, "name", doc.name);
    text_element(out, 1, "description", doc.description);
    doc.walk([&](const FdiStep& step) {
        const std::size_t depth = step.depth + 1;
        if (step.kind == FdiStep::Kind::kFunction) {
            write_function(out, depth, doc.functions[step.index]);
        } else if (step.kind == FdiStep::Kind::kOpenGroup) {
            out += indent(depth) + "<group>\n";
            text_element(out, depth + 1, "name", doc.groups[step.index].name);
            text_element(out, depth + 1, "description", doc.groups[step.index].description);
        } else {
            out += indent(depth) + "</group>\n";
        }
    });
    out += "</segment>\n</fdi>\n";
    return out;
}

}  // namespace olcb::cdi
