// Shared by the pages of lcc-conform --html and lcc-cdi render --html: DOM helpers and the
// memory map. Every text in the data comes from a node or a CDI file and is untrusted: it is
// only ever put into the page with textContent (never parsed as markup), and links only as
// http(s).
"use strict";

const Page = (() => {
    function el(tag, cls, text) {
        const e = document.createElement(tag);
        if (cls) e.className = cls;
        if (text !== undefined && text !== null) e.textContent = String(text);
        return e;
    }

    function hex(n, width) {
        return "0x" + Number(n).toString(16).toUpperCase().padStart(width || 4, "0");
    }

    function plural(n, word) {
        return n + " " + word + (n === 1 ? "" : "s");
    }

    function data() {
        return JSON.parse(document.getElementById("page-data").textContent);
    }

    // The page's state lives in the URL fragment ("#status=FAIL,WARN&segment=2"), so a link or a
    // headless browser can open the page in any state.
    function hashParams() {
        return new URLSearchParams(location.hash.slice(1));
    }

    function setHashParam(key, value) {
        const p = hashParams();
        if (value === null) p.delete(key);
        else p.set(key, value);
        const text = p.toString().replace(/%2C/g, ",");
        history.replaceState(null, "", text ? "#" + text : location.pathname + location.search);
    }

    // A CDI <link>: a real anchor only for http(s) addresses (a javascript: ref stays text).
    function link(l) {
        const text = l.text || l.ref;
        let url = null;
        try {
            const u = new URL(l.ref);
            if (u.protocol === "http:" || u.protocol === "https:") url = u.href;
        } catch (e) {
            url = null;
        }
        if (!url) return el("span", "link-text", text + (l.ref && l.ref !== text ? " (" + l.ref + ")" : ""));
        const a = el("a", "link", text);
        a.href = url;
        a.target = "_blank";
        a.rel = "noopener noreferrer";
        return a;
    }

    function kv(pairs) {
        const dl = el("dl", "kv");
        for (const [k, v] of pairs) {
            if (v === undefined || v === null || v === "") continue;
            dl.append(el("dt", "", k));
            const dd = el("dd");
            if (v instanceof Node) dd.append(v);
            else dd.textContent = String(v);
            dl.append(dd);
        }
        return dl;
    }

    const tip = (() => {
        let box = null;
        return {
            show(lines, x, y) {
                if (!box) {
                    box = el("div");
                    box.id = "mm-tip";
                    document.body.append(box);
                }
                box.textContent = lines.join("\n");
                box.hidden = false;
                const w = box.offsetWidth, h = box.offsetHeight;
                box.style.left = Math.max(4, Math.min(x + 14, innerWidth - w - 8)) + "px";
                box.style.top = (y + 18 + h > innerHeight ? y - h - 10 : y + 18) + "px";
            },
            hide() {
                if (box) box.hidden = true;
            },
        };
    })();

    const kRowLimit = 24;  // rows of one map; bytes per row grow in powers of two to fit
    const kLane = 21;      // pixels per lane of bars

    function bytesPerRow(begin, end) {
        let bpr = 16;
        for (;;) {
            const base = Math.floor(begin / bpr) * bpr;
            if (Math.ceil((end - base) / bpr) <= kRowLimit) return bpr;
            bpr *= 2;
        }
    }

    function rangeText(address, size) {
        return size > 0 ? hex(address) + "\u2013" + hex(address + size - 1) : hex(address);
    }

    // Every bar, gap and overlap of a space, as items with [start, end) and a class.
    function mapItems(space, opt) {
        const items = [];
        space.variables.forEach((v, i) => {
            const cls = opt.classOf ? opt.classOf(v, i) : "t-" + v.type;
            items.push({ kind: "var", i, start: v.address, end: v.address + v.size, cls: "mm-var " + cls, label: v.label });
        });
        space.summaries.forEach((s, i) => {
            const what = s.replicas ? s.group + " " + (s.first_replica + 1) + "\u2013" + (s.first_replica + s.replicas) : "not listed";
            items.push({ kind: "summary", i, start: s.address, end: s.address + s.size, cls: "mm-summary", label: what });
        });
        space.gaps.forEach((g, i) => items.push({ kind: "gap", i, start: g.address, end: g.address + g.size, cls: "mm-gap", label: "" }));
        space.overlaps.forEach((o, i) => items.push({ kind: "overlap", i, start: o.address, end: o.address + o.size, cls: "mm-overlap", label: "" }));
        return items.filter((it) => it.end > it.start);
    }

    // Bars of one row in lanes: each bar in the first lane free at its start, so variables that
    // share bytes sit one above the other.
    function layRow(pieces) {
        const laneEnds = [];
        pieces.sort((a, b) => a.start - b.start || b.end - a.end);
        for (const p of pieces) {
            if (p.item.kind === "gap" || p.item.kind === "overlap") continue;
            let lane = laneEnds.findIndex((end) => end <= p.start);
            if (lane < 0) lane = laneEnds.length;
            laneEnds[lane] = p.end;
            p.lane = lane;
        }
        return Math.max(1, laneEnds.length);
    }

    // The lines of a tooltip, or (inPanel) of the detail panel, which shows values as a table.
    function describe(space, item, opt, inPanel) {
        if (item.kind === "var") {
            const v = space.variables[item.i];
            const lines = [v.replica ? v.name + " (" + v.replica + ")" : v.name, v.type + " \u00b7 " + plural(v.size, "byte") + " \u00b7 " + rangeText(v.address, v.size)];
            return opt.describe ? lines.concat(opt.describe(v, item.i, inPanel)) : lines;
        }
        if (item.kind === "summary") {
            const s = space.summaries[item.i];
            const head = s.replicas
                ? s.group + ": replicas " + (s.first_replica + 1) + "\u2013" + (s.first_replica + s.replicas) + " not listed"
                : "the rest of the segment is not listed";
            return [head, plural(s.variables, "variable") + " \u00b7 " + rangeText(s.address, s.size), "first: " + s.first_name];
        }
        const r = item.kind === "gap" ? space.gaps[item.i] : space.overlaps[item.i];
        const what = item.kind === "gap" ? "gap: no variable uses these bytes" : "overlap: several variables use these bytes";
        return [what, plural(r.size, "byte") + " \u00b7 " + rangeText(r.address, r.size)];
    }

    function buildRows(space, items, rows) {
        const bpr = bytesPerRow(space.begin, space.end);
        const base = Math.floor(space.begin / bpr) * bpr;
        const count = Math.ceil((space.end - base) / bpr);
        const perRow = Array.from({ length: count }, () => []);
        for (const item of items) {
            const first = Math.max(0, Math.floor((item.start - base) / bpr));
            const last = Math.min(count - 1, Math.floor((item.end - 1 - base) / bpr));
            for (let r = first; r <= last; ++r) {
                const rs = base + r * bpr;
                perRow[r].push({ item, start: Math.max(item.start, rs), end: Math.min(item.end, rs + bpr), head: r === first, lane: 0 });
            }
        }
        perRow.forEach((pieces, r) => {
            const rs = base + r * bpr;
            const lanes = layRow(pieces);
            const row = el("div", "mm-row");
            const track = el("div", "mm-track");
            track.style.height = lanes * kLane + 8 + "px";
            row.append(el("span", "mm-addr", hex(rs)), track);
            for (const p of pieces) {
                const bar = el("div", "mm-item " + p.item.cls + (p.head ? " mm-start" : ""), p.head ? p.item.label : "");
                bar.style.left = ((p.start - rs) / bpr) * 100 + "%";
                bar.style.width = ((p.end - p.start) / bpr) * 100 + "%";
                if (p.item.kind !== "gap" && p.item.kind !== "overlap") bar.style.top = p.lane * kLane + "px";
                bar.dataset.item = String(items.indexOf(p.item));
                track.append(bar);
            }
            rows.append(row);
        });
        return bpr;
    }

    function detailPanel(space, item, opt) {
        const panel = el("div", "mm-detail");
        const lines = describe(space, item, opt, true);
        panel.append(el("strong", "", lines[0]));
        for (const line of lines.slice(1)) panel.append(el("div", "", line));
        if (item.kind === "var" && opt.detail) {
            const extra = opt.detail(space.variables[item.i], item.i);
            if (extra) panel.append(extra);
        }
        return panel;
    }

    function legend(entries) {
        const box = el("div", "mm-legend");
        for (const [label, color] of entries) {
            const s = el("span", "", label);
            s.style.setProperty("--swatch", color);
            box.append(s);
        }
        return box;
    }

    // The memory map of one space. opt: title, classOf(variable, i) -> CSS class,
    // describe(variable, i, inPanel) -> more lines for the tooltip or the detail panel, detail(variable, i) -> a node for the panel,
    // legend: [[label, colour]], onPick(variable, i) when a bar is clicked.
    function memoryMap(space, opt) {
        const box = el("section", "mm");
        box.dataset.space = String(space.space);
        box.append(el("h3", "", opt.title));
        const listed = space.variables.length;
        const info = [rangeText(space.begin, space.end - space.begin), plural(space.variable_count, "variable")];
        if (listed < space.variable_count) info.push(listed + " listed, the rest summarized");
        info.push(plural(space.gaps.length, "gap"), plural(space.overlaps.length, "overlap"));
        box.append(el("div", "mm-info", info.join(" \u00b7 ")));
        // The overlap's hatch (page.css --overlap) shares no colour with any verdict or type.
        const common = [["gap", "#e3e7ee"], ["overlap", "repeating-linear-gradient(45deg, #000 0 3px, #f0e442 3px 6px)"]];
        if (space.summaries.length) common.push(["not listed", "#9aa3b5"]);
        box.append(legend((opt.legend || []).concat(common)));
        if (space.end <= space.begin) {
            box.append(el("p", "muted", "no variables"));
            return box;
        }
        const items = mapItems(space, opt);
        const rows = el("div", "mm-rows");
        const bpr = buildRows(space, items, rows);
        rows.title = "";
        box.append(rows, el("div", "mm-info", plural(bpr, "byte") + " per row; hover a bar for details, click to keep them"));
        const holder = el("div");
        box.append(holder);
        const itemOf = (e) => {
            const bar = e.target.closest("[data-item]");
            return bar ? items[Number(bar.dataset.item)] : null;
        };
        rows.addEventListener("mousemove", (e) => {
            const item = itemOf(e);
            if (item) tip.show(describe(space, item, opt), e.clientX, e.clientY);
            else tip.hide();
        });
        rows.addEventListener("mouseleave", () => tip.hide());
        const pick = (item) => {
            for (const b of rows.querySelectorAll(".mm-picked")) b.classList.remove("mm-picked");
            for (const b of rows.querySelectorAll('[data-item="' + items.indexOf(item) + '"]')) b.classList.add("mm-picked");
            holder.replaceChildren(detailPanel(space, item, opt));
            if (item.kind === "var" && opt.onPick) opt.onPick(space.variables[item.i], item.i);
        };
        rows.addEventListener("click", (e) => {
            const item = itemOf(e);
            if (item) pick(item);
        });
        // "#pick=253:4" opens variable 4 of space 253 as a click would (links, headless tests).
        const wanted = /^(\d+):(\d+)$/.exec(hashParams().get("pick") || "");
        if (wanted && Number(wanted[1]) === space.space) {
            const item = items.find((it) => it.kind === "var" && it.i === Number(wanted[2]));
            if (item) setTimeout(() => pick(item), 0);
        }
        return box;
    }

    return { el, hex, plural, data, hashParams, setHashParam, link, kv, memoryMap, rangeText };
})();
