// The lcc-conform --html page: run summary, a check table per node with status filters, and the
// memory map of every space with each variable's verdict. The filter follows the URL fragment:
// "#status=FAIL,WARN" shows only those rows. What is wrong comes first: each table lists its
// FAILs, then its WARNs, then the rest in run order, and a run with any FAIL or WARN opens
// showing only those (issue 34: readers met 42 passing rows before the first FAIL).
"use strict";

(() => {
    const { el, plural } = Page;
    const kStatuses = ["PASS", "FAIL", "WARN", "SKIP"];
    // The colours of page.css (--pass, --fail, --skip, --protected): Okabe-Ito hues, told apart
    // with any colour vision; "overlap" (map.js) is a black-and-yellow hatch, never a verdict's.
    const kVerdicts = [
        ["verified", "#00795a"],
        ["failed", "#c24400"],
        ["skipped", "#737b8c"],
        ["protected", "#a8508a"],
    ];
    const data = Page.data();
    const app = document.getElementById("app");
    const filterButtons = new Map();
    const counters = [];

    // The report gives seconds; people read milliseconds below 10 s.
    function ms(seconds) {
        const n = seconds * 1000;
        return n >= 10000 ? (n / 1000).toFixed(1) + " s" : Math.round(n) + " ms";
    }

    function chips(summary) {
        const box = el("div", "chips");
        for (const s of kStatuses) {
            const chip = el("span", "chip s-" + s.toLowerCase());
            chip.append(el("b", "", summary[s.toLowerCase()] || 0), document.createTextNode(s));
            box.append(chip);
        }
        return box;
    }

    function header() {
        const card = el("section", "card");
        card.append(el("h1", "", "lcc-conform report"));
        const run = data.run || {};
        card.append(
            Page.kv([
                ["Tool", data.tool.name + " " + data.tool.version],
                ["Started", run.started],
                ["Elapsed", run.started ? ms(run.elapsed_s) : ""],
                ["Connection", run.connection],
                ["Command", (run.arguments || []).join(" ")],
                ["Nodes", data.nodes.length ? data.nodes.map((n) => n.id).join(", ") : "none checked"],
            ]),
        );
        card.append(chips(data.run.summary));
        if (run.error) card.append(el("div", "banner error", "The run ended early: " + run.error));
        for (const id of run.late_nodes || []) card.append(el("div", "banner note", "Node " + id + " appeared during the run (not checked)"));
        return card;
    }

    // Without "#status=", the findings when there are any, else every row.
    function defaultFilter() {
        const s = data.run.summary || {};
        return (s.fail || 0) + (s.warn || 0) > 0 ? new Set(["FAIL", "WARN"]) : new Set(kStatuses);
    }

    function readFilter() {
        const text = Page.hashParams().get("status");
        if (text === null) return defaultFilter();
        return new Set(text.toUpperCase().split(",").filter((s) => kStatuses.includes(s)));
    }

    function sameSet(a, b) {
        return a.size === b.size && [...a].every((x) => b.has(x));
    }

    function applyFilter(shown) {
        for (const [status, button] of filterButtons) button.setAttribute("aria-pressed", String(shown.has(status)));
        for (const row of document.querySelectorAll("tr.check")) row.hidden = !shown.has(row.dataset.status);
        for (const update of counters) update();
    }

    function filterBar() {
        const bar = el("div", "filters");
        bar.append(el("span", "muted", "Show:"));
        for (const status of kStatuses) {
            const button = el("button", "filter s-" + status.toLowerCase(), status + " " + (data.run.summary[status.toLowerCase()] || 0));
            button.type = "button";
            button.dataset.status = status;
            button.addEventListener("click", () => {
                const shown = readFilter();
                if (shown.has(status)) shown.delete(status);
                else shown.add(status);
                Page.setHashParam("status", sameSet(shown, defaultFilter()) ? null : kStatuses.filter((s) => shown.has(s)).join(","));
                applyFilter(shown);
            });
            filterButtons.set(status, button);
            bar.append(button);
        }
        return bar;
    }

    function evidence(check) {
        const parts = [];
        if (check.expected || check.seen) {
            const dl = el("dl", "evidence");
            if (check.expected) dl.append(el("dt", "", "expected"), el("dd", "", check.expected));
            if (check.seen) dl.append(el("dt", "", "seen"), el("dd", "", check.seen));
            parts.push(dl);
        }
        if (check.details && check.details.length) {
            const ul = el("ul", "details");
            for (const d of check.details.slice(0, 50)) ul.append(el("li", "", d));
            if (check.details.length > 50) ul.append(el("li", "", "\u2026 " + (check.details.length - 50) + " more"));
            parts.push(ul);
        }
        return parts;
    }

    function checkRow(check) {
        const status = check.status;
        const row = el("tr", "check s-" + status.toLowerCase());
        row.dataset.status = status;
        const st = el("td");
        st.append(el("span", "status s-" + status.toLowerCase(), status));
        const id = el("td", "id");
        id.append(el("code", "", check.id));
        id.title = "category: " + check.category;
        const message = el("td");
        message.append(el("div", "message", check.message), ...evidence(check));
        row.append(st, id, message, el("td", "section", check.section), el("td", "time", ms(check.duration_s || 0)));
        return row;
    }

    function checkTable(node) {
        const table = el("table", "checks");
        const cols = el("colgroup");
        for (const c of ["c-status", "c-id", "c-message", "c-section", "c-time"]) cols.append(el("col", c));
        const head = el("tr");
        for (const h of ["Status", "Check", "Result", "Section", "Time"]) head.append(el("th", "", h));
        const thead = el("thead");
        thead.append(head);
        const body = el("tbody");
        const rank = { FAIL: 0, WARN: 1 };
        const ordered = node.checks.map((check, i) => [rank[check.status] ?? 2, i, check]);
        ordered.sort((a, b) => a[0] - b[0] || a[1] - b[1]);
        for (const [, , check] of ordered) body.append(checkRow(check));
        table.append(cols, thead, body);
        return table;
    }

    function valueLines(v, inPanel) {
        const lines = ["verdict: " + v.verdict + (v.reason ? " \u2014 " + v.reason : "")];
        if (v.original) lines.push("original: " + v.original.value + " [" + v.original.bytes + "]");
        if (inPanel) return lines;  // the panel's table shows the values
        for (const t of v.values || []) {
            const back = t.error ? t.error : t.read_value + " [" + t.read + "]";
            lines.push((t.ok ? "\u2713 " : "\u2717 ") + "wrote " + t.value + " [" + t.written + "] \u2192 " + back);
        }
        return lines;
    }

    function valueTable(v) {
        if (!v.values || !v.values.length) return null;
        const table = el("table");
        const head = el("tr");
        for (const h of ["", "written", "bytes", "read back", "bytes"]) head.append(el("th", "", h));
        table.append(head);
        for (const t of v.values) {
            const row = el("tr");
            row.append(el("td", t.ok ? "ok" : "bad", t.ok ? "\u2713" : "\u2717"), el("td", "", t.value), el("td", "", t.written));
            if (t.error) row.append(el("td", "bad", t.error), el("td", "", t.read || ""));
            else row.append(el("td", "", t.read_value), el("td", "", t.read));
            table.append(row);
        }
        return table;
    }

    function memoryMaps(node) {
        const box = el("div");
        box.append(el("h3", "", "Memory map"));
        if (!node.memory_map || !node.memory_map.length) {
            box.append(el("p", "muted", "No memory map: the node's CDI gave no usable layout."));
            return box;
        }
        for (const space of node.memory_map) {
            const counts = {};
            for (const v of space.variables) counts[v.verdict] = (counts[v.verdict] || 0) + 1;
            box.append(
                Page.memoryMap(space, {
                    title: "Space " + space.space + (space.name ? " \u2014 " + space.name : ""),
                    classOf: (v) => "v-" + v.verdict,
                    describe: (v, i, inPanel) => valueLines(v, inPanel),
                    detail: (v) => valueTable(v),
                    legend: kVerdicts.map(([name, colour]) => [name + " " + (counts[name] || 0), colour]),
                }),
            );
        }
        return box;
    }

    function nodeCard(node) {
        const card = el("section", "card node");
        card.dataset.node = node.id;
        card.append(el("h2", "", node.id + (node.name ? "  " + node.name : "")));
        card.append(chips(node.summary));
        if (node.incomplete) card.append(el("div", "banner error", "The run of this node could not finish: " + node.restore));
        const id = node.identity || {};
        // The checks before the node's identity, so a failing run's first row is on the first
        // screen (tests/e2e/html_page_test.cpp).
        const identity = Page.kv([
            ["Manufacturer", id.manufacturer],
            ["Model", id.model],
            ["Hardware", id.hardware_version],
            ["Software", id.software_version],
            ["User name", id.user_name],
            ["User description", id.user_description],
            ["Started", node.started],
            ["Elapsed", ms(node.elapsed_s)],
            ["Memory afterwards", node.restore],
        ]);
        card.append(el("h3", "", "Checks"));
        const shown = el("div", "shown-count");
        counters.push(() => {
            const rows = card.querySelectorAll("tr.check");
            const visible = [...rows].filter((r) => !r.hidden).length;
            shown.textContent = visible + " of " + plural(rows.length, "check") + " shown";
        });
        card.append(shown, checkTable(node), el("h3", "", "Node"), identity, memoryMaps(node));
        return card;
    }

    document.title = "lcc-conform" + (data.nodes.length ? ": " + data.nodes.map((n) => n.id).join(", ") : "");
    app.append(header(), filterBar());
    for (const node of data.nodes) app.append(nodeCard(node));
    applyFilter(readFilter());
    window.addEventListener("hashchange", () => applyFilter(readFilter()));
    document.body.dataset.ready = "true";
})();
