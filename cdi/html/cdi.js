// The lcc-cdi render --html page: the CDI as a configuration tool shows it (segments as tabs,
// groups, replications with their repname numbering, the 1.4 hints) and the memory map of each
// segment's space. "#segment=N" (1-based) opens segment N. Nothing here talks to a node: the
// controls show the defaults and constraints only.
"use strict";

(() => {
    const { el, hex } = Page;
    const data = Page.data();
    const app = document.getElementById("app");
    const kTypes = {
        int: "#2f6fc4",
        string: "#1f8a78",
        eventid: "#c7721a",
        float: "#7b4fc4",
        action: "#b23a6b",
        blob: "#5d6677",
        bit: "#5b8fd6",
    };
    const byId = new Map();  // element id -> {row, groups}
    const tabs = [];
    let uid = 0;

    function header() {
        const card = el("section", "card");
        const id = data.identification;
        card.append(el("h1", "", id ? (id.manufacturer + " " + id.model).trim() || "CDI" : "CDI"));
        card.append(
            Page.kv([
                ["File", data.source],
                ["Manufacturer", id && id.manufacturer],
                ["Model", id && id.model],
                ["Hardware version", id && id.hardware_version],
                ["Software version", id && id.software_version],
                ["Link", id && id.link ? Page.link(id.link) : null],
                ["ACDI", data.acdi ? "fixed " + data.acdi.fixed + ", var " + data.acdi.var + ": space 252 manufacturer data, space 251 user name and description" : null],
            ]),
        );
        return card;
    }

    function addressOf(e, groups) {
        if (e.address === null || e.address === undefined) return null;
        let a = e.address;
        for (const g of groups) a += g.replica * g.stride;
        return a;
    }

    function hintBadges(e) {
        const h = e.hints || {};
        const out = [];
        if (h.slider) out.push("slider");
        if (h.radiobutton) out.push("radiobutton");
        if (h.checkbox) out.push("checkbox");
        if (h.read_only) out.push("readOnly");
        if (h.hideable) out.push(h.hidden ? "hideable, hidden" : "hideable");
        return out.map((t) => el("span", "hint", t));
    }

    function intRange(e) {
        const bits = 8 * e.size;
        const signed = e.signed;
        const lo = e.min !== undefined ? Number(e.min) : signed ? -(2 ** (bits - 1)) : 0;
        const hi = e.max !== undefined ? Number(e.max) : signed ? 2 ** (bits - 1) - 1 : 2 ** bits - 1;
        return [lo, hi];
    }

    function select(e, readOnly) {
        const s = el("select");
        for (const entry of e.map) {
            const o = el("option", "", entry.value);
            o.value = entry.property;
            if (e.default !== undefined && String(e.default) === entry.property) o.selected = true;
            s.append(o);
        }
        s.disabled = readOnly;
        return s;
    }

    function radios(e, readOnly) {
        const box = el("span");
        const name = "r" + ++uid;
        for (const entry of e.map) {
            const label = el("label", "radio");
            const input = el("input");
            input.type = "radio";
            input.name = name;
            input.value = entry.property;
            input.checked = e.default !== undefined && String(e.default) === entry.property;
            input.disabled = readOnly;
            label.append(input, document.createTextNode(" " + entry.value));
            box.append(label);
        }
        return box;
    }

    function checkbox(e, readOnly) {
        const label = el("label");
        const input = el("input");
        input.type = "checkbox";
        const on = e.map.length > 1 ? e.map[1] : null;
        input.checked = on !== null && e.default !== undefined && String(e.default) === on.property;
        input.disabled = readOnly;
        label.append(input, document.createTextNode(" " + (on ? on.value : "")));
        return label;
    }

    function slider(e, readOnly) {
        const box = el("span");
        const [lo, hi] = intRange(e);
        const input = el("input");
        input.type = "range";
        input.min = String(lo);
        input.max = String(hi);
        input.value = String(e.default !== undefined ? Number(e.default) : lo);
        input.disabled = readOnly;
        const tick = e.hints.slider.tick_spacing;
        if (tick > 0 && (hi - lo) / tick <= 200) {
            const list = el("datalist");
            list.id = "ticks" + ++uid;
            for (let v = lo; v <= hi; v += tick) {
                const o = el("option");
                o.value = String(v);
                list.append(o);
            }
            input.setAttribute("list", list.id);
            box.append(list);
        }
        box.append(input);
        if (e.hints.slider.show_value) {
            const out = el("output", "", input.value);
            input.addEventListener("input", () => (out.textContent = input.value));
            box.append(out);
        }
        return box;
    }

    function numberInput(e, readOnly, step) {
        const input = el("input");
        input.type = "number";
        input.step = step;
        if (e.min !== undefined) input.min = String(e.min);
        if (e.max !== undefined) input.max = String(e.max);
        if (e.default !== undefined) input.value = String(e.default);
        input.disabled = readOnly;
        return input;
    }

    function textInput(e, readOnly, placeholder) {
        const input = el("input");
        input.type = "text";
        if (e.kind === "string" && e.size > 0) input.maxLength = e.size - 1;
        if (e.default !== undefined) input.value = String(e.default);
        if (placeholder) input.placeholder = placeholder;
        input.disabled = readOnly;
        return input;
    }

    function control(e, readOnly) {
        const h = e.hints || {};
        switch (e.kind) {
            case "int":
            case "bit":
                if (e.map && h.radiobutton) return radios(e, readOnly);
                if (e.map && h.checkbox) return checkbox(e, readOnly);
                if (e.map) return select(e, readOnly);
                if (h.slider) return slider(e, readOnly);
                return numberInput(e, readOnly, "1");
            case "float":
                return numberInput(e, readOnly, "any");
            case "string":
                return e.map ? select(e, readOnly) : textInput(e, readOnly, "");
            case "eventid":
                return e.map ? select(e, readOnly) : textInput(e, readOnly, "00.00.00.00.00.00.00.00");
            case "action": {
                const b = el("button", "", e.button || e.name || "Trigger");
                b.type = "button";
                if (e.dialog) b.title = e.dialog;
                b.disabled = readOnly;
                return b;
            }
            case "blob":
                return el("span", "muted", "blob of " + e.size + " bytes" + (e.mode ? ", mode " + e.mode : ""));
            default:
                return el("span", "muted", "<" + e.tag + "> of " + e.size + " bytes (unknown element)");
        }
    }

    function variable(e, ctx) {
        const row = el("div", "var");
        row.dataset.element = String(e.id);
        row.dataset.kind = e.kind;
        const label = el("div", "label", e.name || "(" + e.tag + ")");
        const ctl = el("div", "control");
        ctl.append(control(e, ctx.readOnly));
        const meta = el("div", "meta");
        const update = () => {
            const a = addressOf(e, ctx.groups);
            meta.textContent = e.tag + "(" + e.size + ")" + (a !== null ? " @ " + hex(a) : "");
            meta.append(...hintBadges(e));
        };
        update();
        for (const g of ctx.groups) g.listeners.push(update);
        row.append(label, ctl, meta);
        if (e.description || e.link) {
            const help = el("div", "help", e.description || "");
            if (e.link) help.append(document.createTextNode(" "), Page.link(e.link));
            row.append(help);
        }
        byId.set(e.id, { row, groups: ctx.groups });
        return row;
    }

    function replicaName(e, i) {
        return i < e.replica_names.length && e.replica_names[i] ? e.replica_names[i] : "#" + (i + 1);
    }

    // Tabs for a few replicas, a number field for many; the body is built once and its
    // addresses follow the chosen replica.
    function replicaPicker(e, state, title) {
        const box = el("div", "replicas");
        const count = e.replication;
        const named = el("span", "replica-name");
        const buttons = [];
        let number = null;
        state.set = (i) => {
            state.replica = Math.max(0, Math.min(count - 1, i));
            buttons.forEach((b, k) => b.setAttribute("aria-selected", String(k === state.replica)));
            if (number) number.value = String(state.replica + 1);
            named.textContent = replicaName(e, state.replica);
            title.textContent = (e.name || "Group") + " \u2014 " + replicaName(e, state.replica);
            for (const update of state.listeners) update();
        };
        if (count <= 16) {
            for (let i = 0; i < count; ++i) {
                const b = el("button", "replica", replicaName(e, i));
                b.type = "button";
                b.addEventListener("click", () => state.set(i));
                buttons.push(b);
                box.append(b);
            }
        } else {
            const prev = el("button", "replica", "\u25c0");
            const next = el("button", "replica", "\u25b6");
            prev.type = next.type = "button";
            number = el("input");
            number.type = "number";
            number.min = "1";
            number.max = String(count);
            number.addEventListener("change", () => state.set(Number(number.value) - 1));
            prev.addEventListener("click", () => state.set(state.replica - 1));
            next.addEventListener("click", () => state.set(state.replica + 1));
            box.append(prev, number, next, el("span", "muted", "of " + count), named);
        }
        box.append(el("span", "muted", " \u00b7 " + count + " replicas, " + Page.plural(e.stride, "byte") + " each"));
        return box;
    }

    function group(e, ctx) {
        const h = e.hints || {};
        const readOnly = ctx.readOnly || !!h.read_only;
        let box, title;
        if (h.hideable) {
            box = el("details", "group hideable" + (readOnly ? " readonly" : ""));
            box.open = !h.hidden;
            title = el("summary", "", e.name || "Group");
            box.append(title);
        } else {
            box = el("fieldset", "group" + (readOnly ? " readonly" : ""));
            title = el("legend", "", e.name || "Group");
            box.append(title);
        }
        box.dataset.element = String(e.id);
        if (e.description) box.append(el("div", "description", e.description));
        if (e.link) box.append(Page.link(e.link));
        const badges = hintBadges(e);
        if (badges.length) box.append(el("div", "", ""), ...badges);
        let groups = ctx.groups;
        if (e.replication > 1) {
            const state = { replica: 0, stride: e.stride, listeners: [] };
            box.append(replicaPicker(e, state, title));
            groups = groups.concat([state]);
            state.set(0);
        }
        const inner = { groups, readOnly };
        for (const child of e.children) box.append(element(child, inner));
        byId.set(e.id, { row: box, groups: ctx.groups });
        return box;
    }

    function element(e, ctx) {
        return e.kind === "group" ? group(e, ctx) : variable(e, ctx);
    }

    function showTab(index) {
        tabs.forEach((t, k) => {
            t.button.setAttribute("aria-selected", String(k === index));
            t.panel.hidden = k !== index;
        });
        Page.setHashParam("segment", index === 0 ? null : String(index + 1));
    }

    // A click on a bar of the memory map opens the variable in the form.
    function pick(v) {
        const target = byId.get(v.element);
        if (!target) return;
        showTab(v.segment);
        const replicas = v.replicas || [];
        target.groups.forEach((g, k) => g.set(replicas[k] || 0));
        target.row.scrollIntoView({ block: "center" });
        target.row.classList.add("flash");
        setTimeout(() => target.row.classList.remove("flash"), 1200);
    }

    function segmentPanel(segment, index) {
        const panel = el("section", "panel");
        panel.setAttribute("role", "tabpanel");
        panel.dataset.segment = String(index);
        panel.append(el("div", "muted", "space " + segment.space + ", origin " + segment.origin));
        if (segment.description) panel.append(el("div", "description", segment.description));
        if (segment.link) panel.append(Page.link(segment.link));
        // The map first, folded away by a click: where the bytes go is what a form cannot show.
        const space = data.memory_map.find((m) => m.space === segment.space);
        if (space) {
            const others = space.segments.filter((s) => s !== index).length;
            const used = {};
            for (const v of space.variables) used[v.type] = true;
            const fold = el("details", "map-fold");
            fold.open = true;
            fold.append(el("summary", "", "Memory map"));
            fold.append(
                Page.memoryMap(space, {
                    title: "Space " + space.space + (others ? " (shared with " + Page.plural(others, "other segment") + ")" : ""),
                    classOf: (v) => "t-" + (kTypes[v.type] ? v.type : "other"),
                    legend: Object.keys(used).map((t) => [t, kTypes[t] || "#8a6d3b"]),
                    onPick: pick,
                }),
            );
            panel.append(fold);
        }
        const ctx = { groups: [], readOnly: false };
        for (const child of segment.children) panel.append(element(child, ctx));
        return panel;
    }

    document.title = "CDI: " + (data.identification ? data.identification.model || data.source : data.source);
    app.append(header());
    const bar = el("div", "tabs");
    bar.setAttribute("role", "tablist");
    app.append(bar);
    data.segments.forEach((segment, index) => {
        const button = el("button", "tab", segment.name || "Segment " + (index + 1) + " (space " + segment.space + ")");
        button.type = "button";
        button.setAttribute("role", "tab");
        button.addEventListener("click", () => showTab(index));
        bar.append(button);
        const panel = segmentPanel(segment, index);
        app.append(panel);
        tabs.push({ button, panel });
    });
    if (!tabs.length) app.append(el("p", "muted", "This CDI has no segments."));
    const wanted = Number(Page.hashParams().get("segment") || "1") - 1;
    if (tabs.length) showTab(wanted >= 0 && wanted < tabs.length ? wanted : 0);
    document.body.dataset.ready = "true";
})();
