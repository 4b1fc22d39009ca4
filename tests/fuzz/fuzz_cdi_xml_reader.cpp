// libFuzzer target, differential: whatever the fast XML reader accepts, pugixml (the reader
// it stands in for) must accept too and yield the same element tree: names, offsets, first
// texts and attributes. A disagreement traps.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "cdi/pugixml_tree.hpp"
#include "cdi/simple_xml_reader.hpp"
#include "cdi/xml_tree.hpp"

namespace {

using namespace olcb::cdi;

constexpr std::size_t kDepth = 144;

// Every element in document order with its depth, name, offset, text and attributes.
std::string dump(const XmlTree& tree) {
    std::string out;
    const auto walk = [&out](XmlElement e, std::size_t depth, const auto& self) -> void {
        for (; e; e = e.next_sibling()) {
            out += std::to_string(depth) + ' ';
            out += e.name();
            out += '@' + std::to_string(e.offset()) + '[';
            out += e.text();
            out += ']';
            for (const XmlAttribute& a : e.attributes()) {
                out += ' ';
                out += a.name;
                out += "=[";
                out += a.value;
                out += ']';
            }
            out += '\n';
            self(e.first_child(), depth + 1, self);
        }
    };
    walk(tree.root(), 0, walk);
    return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    XmlTree fast(text);
    if (!read_simple_xml(text, kDepth, fast)) return 0;
    pugi::xml_document xml;
    if (!xml.load_buffer(text.data(), text.size(), kPugixmlOptions, pugi::encoding_utf8)) {
        __builtin_trap();  // accepted what pugixml refuses
    }
    XmlTree reference(text);
    copy_pugixml_elements(xml.document_element(), reference);
    if (dump(fast) != dump(reference)) __builtin_trap();
    return 0;
}
