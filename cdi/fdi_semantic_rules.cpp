#include "cdi/fdi_semantic_rules.hpp"

#include <string>
#include <unordered_map>
#include <utility>

namespace olcb::cdi {
namespace {

std::string label(const FdiFunction& f) {
    std::string out = "<function> F" + std::to_string(f.number);
    if (!f.name.empty()) out += " \"" + f.name + "\"";
    return out;
}

class FdiChecker {
public:
    Diagnostics run(const FdiDocument& doc, FdiSchemaVersion schema) {
        segment_attributes(doc);
        if (schema == FdiSchemaVersion::kV1_1) icons(doc);
        std::unordered_map<std::uint32_t, std::uint32_t> first_line;
        for (const FdiFunction& f : doc.functions) {
            values(f);
            const auto [it, fresh] = first_line.emplace(f.number, f.line);
            if (!fresh) {
                warning(f, "number " + std::to_string(f.number) + " is also described at line " +
                               std::to_string(it->second) +
                               ": a throttle would show two buttons for one function (advice: "
                               "no clause forbids it)");
            }
        }
        return std::move(out_);
    }

private:
    void warning(const FdiFunction& f, const std::string& message) {
        out_.push_back({Severity::kWarning, f.line, label(f) + ": " + message});
    }

    // §5.1.2: "The 'space' and 'origin' attributes are reserved, and new implementations should
    // omit them."
    void segment_attributes(const FdiDocument& doc) {
        if (!doc.space_given && !doc.origin_given) return;
        const std::string which = doc.space_given && doc.origin_given ? "'space' and 'origin'"
                                  : doc.space_given                   ? "'space'"
                                                                      : "'origin'";
        out_.push_back({Severity::kWarning, doc.segment_line,
                        "<segment>: " + which +
                            " given; the attributes are reserved and new implementations should "
                            "omit them (FunctionDescriptionInformationS §5.1.2)"});
    }

    // The standard defines <icon> (§5.1.4, Appendix A) but the published 1.1 schema file lacks
    // it: the embedded 1.1 accepts it, and a reader using the published file would not.
    void icons(const FdiDocument& doc) {
        std::size_t count = 0;
        const FdiFunction* first = nullptr;
        for (const FdiFunction& f : doc.functions) {
            if (!f.icon) continue;
            ++count;
            if (first == nullptr) first = &f;
        }
        if (first == nullptr) return;
        warning(*first, "<icon> (" + std::to_string(count) +
                            " function(s) have one) is defined by FunctionDescriptionInformationS "
                            "§5.1.4 and Appendix A but missing from the published "
                            "schema/fdi/1/1/fdi.xsd: a reader validating against that file "
                            "refuses this FDI");
    }

    // §5.1.4: an analog function takes "unsigned integer values accepted between the optional
    // <min> and <max> sub-elements (inclusive)", 0 and 255 when absent; Set Function carries 16
    // bits (FDI-TN §3.1). The schema documents <min>/<max> as used only for analog functions.
    void values(const FdiFunction& f) {
        if (f.kind != FunctionKind::kAnalog) {
            if (f.min || f.max) {
                warning(f,
                        "<min>/<max> are used only when kind is analog (schema annotation); "
                        "a " +
                            std::string(function_kind_name(f.kind)) + " function ignores them");
            }
            return;
        }
        const std::string range =
            std::to_string(f.value_min()) + ".." + std::to_string(f.value_max());
        if (f.value_min() < 0 || f.value_max() < 0) {
            warning(f, "range " + range +
                           " is negative; an analog function takes unsigned integer values "
                           "(FunctionDescriptionInformationS §5.1.4)");
        }
        if (f.value_min() > f.value_max()) {
            warning(f, "range " + range +
                           " accepts no value: values lie between <min> and <max> inclusive, "
                           "0 and 255 when absent (FunctionDescriptionInformationS §5.1.4)");
        }
        if (f.value_max() > kMaxFunctionValue) {
            warning(f, "<max> " + std::to_string(f.value_max()) +
                           " is above 65535, the largest value Train Control's Set Function "
                           "carries (FunctionDescriptionInformationTN §3.1)");
        }
    }

    Diagnostics out_;
};

}  // namespace

Diagnostics check_fdi_semantics(const FdiDocument& doc, FdiSchemaVersion schema) {
    return FdiChecker().run(doc, schema);
}

}  // namespace olcb::cdi
