// foon2asp explore: the page's address holds the whole question (goal=... plus one parameter
// per control, named as the command-line options); every change asks the server again.
"use strict";

const $ = (id) => document.getElementById(id);
const NUMBERS = ["time-limit", "human-steps", "max-units"];
const TEXT_LISTS = ["forbid-object", "require-object"];
// parameters with no control of their own, kept as the address gives them
const KEPT = ["require-motion", "max-depth"];
const MEASURES = ["units", "success", "inputs", "depth", "cost"];
// what the search baselines ignore
const CONSTRAINTS = ["forbid-motion", "forbid-object", "require-motion", "require-object", "rule", "max-units", "max-depth", "human-steps"];

let info = { objectives: ["units", "success", "inputs", "depth"], seconds: 10, agents: "robot=1" };
let controller = null; // the answers being fetched for the page on screen
let part = null; // the relevant part of the goal on screen: {goal, motions, kitchen}
let pending = 0;
let since = 0;
let ticker = null;

class AnswerError extends Error {}

function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs)) {
    if (key === "class") node.className = value;
    else if (value !== null && value !== undefined && value !== false) node.setAttribute(key, value === true ? "" : value);
  }
  for (const child of children.flat()) {
    if (child !== null && child !== undefined) node.append(child instanceof Node ? child : String(child));
  }
  return node;
}

function number(value) {
  if (typeof value !== "number") return String(value);
  if (Number.isInteger(value)) return String(value);
  return Math.abs(value) < 0.001 ? value.toExponential(3) : String(Number(value.toPrecision(4)));
}

async function getJSON(url, signal) {
  const response = await fetch(url, { signal });
  let body = null;
  try {
    body = await response.json();
  } catch (e) {
    throw new AnswerError(`${response.status} ${response.statusText}`);
  }
  if (!response.ok) throw new AnswerError(body.error || `${response.status} ${response.statusText}`);
  return body;
}

// ------------------------------------------------------------------ the address and the controls

function address() {
  return new URLSearchParams(location.search);
}

function objectiveOf(params) {
  return (params.get("objective") || "units").split(",").map((s) => s.trim()).filter(Boolean);
}

function fillControls(params) {
  $("goal").value = params.get("goal") || "";
  const [first, second] = objectiveOf(params);
  $("objective-1").value = first || "units";
  $("objective-2").value = second || "";
  for (const name of NUMBERS) $(name).value = params.get(name) || "";
  for (const name of TEXT_LISTS) $(name).value = params.getAll(name).join(", ");
  $("rule").value = params.getAll("rule").join("\n");
  $("agents").value = params.get("agents") || "";
  drawChoices(params);
}

function fromControls() {
  const now = address();
  const out = new URLSearchParams();
  if (now.get("goal")) out.set("goal", now.get("goal"));
  const first = $("objective-1").value;
  const second = $("objective-2").value;
  const objective = second && second !== first ? `${first},${second}` : first;
  if (objective && objective !== "units") out.set("objective", objective);
  for (const name of NUMBERS) if ($(name).value.trim()) out.set(name, $(name).value.trim());
  if ($("agents").value.trim()) out.set("agents", $("agents").value.trim());
  for (const box of document.querySelectorAll("#motions input:not(:checked)")) out.append("forbid-motion", box.value);
  for (const name of TEXT_LISTS) {
    for (const label of $(name).value.split(",")) if (label.trim()) out.append(name, label.trim());
  }
  for (const name of KEPT) for (const value of now.getAll(name)) out.append(name, value);
  if ($("rule").value.trim()) out.append("rule", $("rule").value.trim());
  for (const box of document.querySelectorAll("#kitchen input:not(:checked)")) out.append("without", box.value);
  return out;
}

function drawChoices(params) {
  const goal = params.get("goal");
  const known = part && part.goal === goal ? part : { motions: [], kitchen: [] };
  const forbidden = new Set(params.getAll("forbid-motion"));
  const motions = [...new Set([...known.motions, ...forbidden])].sort();
  boxes($("motions"), motions.map((m) => ({ value: m, text: m, on: !forbidden.has(m) })));
  const without = new Set(params.getAll("without"));
  const items = known.kitchen.map((k) => k.text);
  for (const item of without) if (!items.includes(item)) items.push(item);
  boxes($("kitchen"), items.map((t) => ({ value: t, text: t, on: !without.has(t) })));
}

function boxes(fieldset, choices) {
  const holder = fieldset.querySelector(".boxes");
  holder.replaceChildren(
    ...choices.map((c) => el("label", {}, el("input", { type: "checkbox", value: c.value, checked: c.on }), " ", c.text))
  );
  fieldset.hidden = choices.length === 0;
}

function navigate(params) {
  const query = params.toString();
  if (query !== location.search.replace(/^\?/, "")) history.pushState(null, "", query ? `?${query}` : location.pathname);
  show();
}

// ------------------------------------------------------------------ working, errors

function startWorking() {
  pending += 1;
  if (pending > 1) return;
  since = performance.now();
  const limit = Number(address().get("time-limit")) || info.seconds;
  ticker = setInterval(() => {
    const seconds = (performance.now() - since) / 1000;
    $("working").hidden = seconds < 0.15;
    $("working-text").textContent = `working… ${seconds.toFixed(1)} s (time limit ${limit} s)`;
  }, 100);
}

function stopWorking() {
  pending = Math.max(0, pending - 1);
  if (pending > 0) return;
  clearInterval(ticker);
  $("working").hidden = true;
}

function showError(message) {
  $("error").textContent = message ? `error: ${message}` : "";
  $("error").hidden = !message;
}

async function ask(path, params, signal) {
  startWorking();
  try {
    return await getJSON(`${path}?${params.toString()}`, signal);
  } finally {
    stopWorking();
  }
}

// ------------------------------------------------------------------ the answers

async function show() {
  const params = address();
  if (controller) controller.abort();
  controller = new AbortController();
  const signal = controller.signal;
  fillControls(params);
  showError("");
  const goal = params.get("goal");
  document.title = goal ? `${goal} — foon2asp explore` : "foon2asp explore";
  if (!goal) {
    $("result").hidden = true;
    document.body.dataset.shown = params.toString();
    return;
  }
  let tree;
  try {
    tree = await ask("/api/tree", params, signal);
  } catch (e) {
    if (e.name === "AbortError") return;
    $("result").hidden = true;
    showError(e.message);
    document.body.dataset.shown = params.toString();
    return;
  }
  part = { goal, motions: tree.part.motions, kitchen: tree.part.kitchen };
  drawChoices(params);
  $("result").hidden = false;
  drawTree(tree, params);
  document.body.dataset.shown = params.toString(); // the question whose answer is on screen
  drawBaselines(null);
  $("schedule-summary").textContent = "";
  const later = [
    ask("/api/baselines", params, signal).then(drawBaselines),
    ask("/api/schedule", params, signal).then(drawSchedule),
  ];
  if (tree.status === "unreachable" || tree.status === "infeasible") {
    $("missing").textContent = "missing: looking for what to buy…";
    later.unshift(ask("/api/missing", params, signal).then(drawMissing));
  }
  for (const answer of later) {
    answer.catch((e) => {
      if (e.name !== "AbortError") showError(e.message);
    });
  }
  const settled = await Promise.allSettled(later);
  if (!signal.aborted && settled.length) document.body.dataset.complete = params.toString();
}

function drawTree(tree, params) {
  $("goal-text").textContent = tree.goal.text;
  let status = tree.status;
  if (tree.proven_by) status += ` (proven by ${tree.proven_by})`;
  if (tree.gap) status += `, gap ${(100 * tree.gap).toFixed(1)} %`;
  $("status").replaceChildren(
    el("strong", { class: `status ${tree.status}` }, status),
    el("span", { id: "time" }, ` in ${number(tree.time_s)} s`)
  );
  $("reason").textContent = tree.reason ? `${tree.status}: ${tree.reason}` : tree.note || "";
  $("missing").textContent = "";
  const ranked = objectiveOf(params);
  const rows = MEASURES.filter((m) => m in tree.cost).map((m) =>
    el(
      "tr",
      { class: ranked.includes(m) ? "ranked" : null },
      el("th", {}, m),
      el("td", {}, number(tree.cost[m])),
      el("td", { class: "quiet" }, ranked.includes(m) ? `objective ${ranked.indexOf(m) + 1}` : "")
    )
  );
  $("costs").replaceChildren(...rows);
  $("tree").innerHTML = tree.svg || "";
  $("tree").hidden = !tree.svg;
  readable($("tree"));
  $("steps").replaceChildren(...stepItems(tree.steps, new Set()));
  $("steps").parentElement.hidden = tree.steps.length === 0;
  const warnings = tree.warnings || [];
  $("rule-warnings").replaceChildren(...warnings.map((w) => el("li", {}, `warning: ${w}`)));
}

function drawMissing(missing) {
  let text = `missing: no items to buy make it (${missing.status})`;
  if (missing.items.length) text = `missing: buy ${missing.items.join("; ")}`;
  else if (missing.status === "infeasible") text = "missing: no item to buy gives a tree: the constraints rule out every tree";
  $("missing").textContent = text;
}

function stepItems(steps, differs) {
  return steps.map((s, k) =>
    el(
      "li",
      { class: differs.has(k) ? "differs" : null },
      el("strong", {}, s.motion),
      s.human ? el("span", { class: "human" }, " [human]") : null,
      el("div", { class: "io" }, `in: ${s.inputs.join("; ")}`),
      el("div", { class: "io" }, `out: ${s.outputs.join("; ")}`)
    )
  );
}

function distanceText(distance) {
  if (!distance) return "no tree to compare";
  const parts = [];
  for (const m of MEASURES) {
    if (!(m in distance) || distance[m] === null) continue;
    if (m === "success") parts.push(`success ×${number(distance[m])}`);
    else parts.push(`${m} ${distance[m] >= 0 ? "+" : ""}${number(distance[m])}`);
  }
  return parts.join(", ");
}

function drawBaselines(answer) {
  const cards = document.querySelector("#baselines .cards");
  if (!answer) {
    cards.replaceChildren();
    $("baselines-note").textContent = "";
    return;
  }
  const asked = address();
  const constrained = CONSTRAINTS.some((name) => asked.has(name));
  $("baselines-note").textContent = constrained
    ? "Distances are to the proven optimum without your constraints (the search baselines ignore them)."
    : "Distances are to the proven tree above; steps it does not use are marked.";
  cards.replaceChildren(
    ...answer.methods.map((m) => {
      const verdict = m.status === "not-found" ? "no tree" : m.valid ? "valid" : `INVALID: ${m.problem || "not derivable"}`;
      const drawing = el("div", { class: "drawing" });
      drawing.innerHTML = m.svg || "";
      for (const k of m.differs) {
        for (const node of drawing.querySelectorAll("g.node")) {
          const title = node.querySelector("title");
          if (title && title.textContent === `u${k + 1}`) node.classList.add("differs");
        }
      }
      const card = el(
        "article",
        { class: `card ${m.valid ? "valid" : "invalid"}`, "data-method": m.method },
        el("h3", {}, m.method),
        el("p", {}, el("strong", { class: m.valid ? "valid" : "invalid" }, verdict)),
        el("p", { class: "distance" }, `distance to the optimum: ${distanceText(m.distance)}`),
        el("p", { class: "quiet" }, `${m.differs.length} of ${m.steps.length} steps not in the optimum`),
        drawing,
        el("details", {}, el("summary", {}, "Steps"), el("ol", { class: "steps" }, ...stepItems(m.steps, new Set(m.differs))))
      );
      return card;
    })
  );
  for (const drawing of cards.querySelectorAll(".drawing")) readable(drawing);
}

function drawSchedule(answer) {
  const parts = [`${answer.status}`];
  if (answer.makespan !== null) parts.push(`makespan ${number(answer.makespan)} s on ${answer.agents.join(", ")}`);
  if (answer.baseline !== null && answer.baseline !== undefined) parts.push(`list scheduling ${number(answer.baseline)} s`);
  if (answer.bounds && answer.bounds.lower !== undefined) parts.push(`lower bound ${number(answer.bounds.lower)} s`);
  $("schedule-summary").textContent = parts.join(" · ");
  const head = el("tr", {}, ...["step", "motion", "agent", "start (s)", "end (s)", "duration (s)"].map((h) => el("th", {}, h)));
  const rows = answer.rows.map((r) =>
    el("tr", {}, ...[r.step, r.motion, r.agent, number(r.start), number(r.end), number(r.duration)].map((v) => el("td", {}, v)))
  );
  $("durations").replaceChildren(head, ...rows);
  $("gantt").innerHTML = answer.svg || "";
  readable($("gantt"));
}

// a drawing whose smallest text would be under 12 px is drawn larger (the tree's is not); a drawing
// wider than its frame is shown from its middle, and a button fits it to the frame (smaller text)
function readable(holder) {
  const svg = holder.querySelector("svg");
  if (!svg) return;
  holder.classList.remove("fit");
  if (!holder.previousElementSibling || !holder.previousElementSibling.classList.contains("fit-button")) {
    const button = el("button", { type: "button", class: "fit-button" }, "fit to the frame");
    button.addEventListener("click", () => {
      holder.classList.toggle("fit");
      button.textContent = holder.classList.contains("fit") ? "full size" : "fit to the frame";
    });
    holder.before(button);
  } else {
    holder.previousElementSibling.textContent = "fit to the frame";
  }
  let least = Infinity;
  for (const text of svg.querySelectorAll("text")) {
    const ctm = text.getScreenCTM();
    const size = parseFloat(text.getAttribute("font-size"));
    if (ctm && size) least = Math.min(least, size * ctm.a);
  }
  if (least < 12 && least > 0) {
    for (const side of ["width", "height"]) {
      const found = /^([0-9.]+)([a-z]*)$/.exec(svg.getAttribute(side) || "");
      if (found) svg.setAttribute(side, `${(parseFloat(found[1]) * 12) / least}${found[2]}`);
    }
  }
  centre(holder);
  requestAnimationFrame(() => centre(holder)); // once the page around it is laid out
}

function centre(holder) {
  holder.scrollLeft = Math.max(0, (holder.scrollWidth - holder.clientWidth) / 2);
  holder.scrollTop = 0;
}

// ------------------------------------------------------------------ exports

async function download(fmt) {
  $("export-error").hidden = true;
  startWorking();
  try {
    const response = await fetch(`/api/export/${fmt}?${address().toString()}`);
    if (!response.ok) {
      const body = await response.json().catch(() => ({ error: response.statusText }));
      throw new AnswerError(body.error);
    }
    const found = /filename="([^"]+)"/.exec(response.headers.get("Content-Disposition") || "");
    const link = el("a", { href: URL.createObjectURL(await response.blob()), download: found ? found[1] : fmt });
    document.body.append(link);
    link.click();
    link.remove();
  } catch (e) {
    $("export-error").textContent = `error: ${e.message}`;
    $("export-error").hidden = false;
  } finally {
    stopWorking();
  }
}

// ------------------------------------------------------------------ the goal box

let suggestTimer = null;
let suggestAsked = null;

function suggest() {
  clearTimeout(suggestTimer);
  suggestTimer = setTimeout(async () => {
    if (suggestAsked) suggestAsked.abort();
    suggestAsked = new AbortController();
    const text = $("goal").value;
    try {
      const found = await getJSON(`/api/suggest?q=${encodeURIComponent(text)}`, suggestAsked.signal);
      $("hint").textContent = found.count > found.objects.length ? `${found.count} objects match; the first ${found.objects.length} shown` : "";
      listSuggestions(found.objects);
    } catch (e) {
      if (e.name === "AbortError") return;
      $("hint").textContent = e.message;
      listSuggestions([]);
    }
  }, 120);
}

function listSuggestions(objects) {
  const list = $("suggestions");
  list.replaceChildren(
    ...objects.map((o, k) => {
      const where = [o.kitchen ? "kitchen" : null, o.made ? `made by ${o.made} unit${o.made === 1 ? "" : "s"}` : null];
      return el(
        "li",
        { role: "option", id: `suggestion-${k}`, "data-text": o.text },
        o.text,
        el("span", { class: "quiet" }, ` #${o.id}${where.filter(Boolean).length ? " · " + where.filter(Boolean).join(", ") : ""}`)
      );
    })
  );
  list.hidden = objects.length === 0;
  $("goal").setAttribute("aria-expanded", String(!list.hidden));
}

function pick(text) {
  $("goal").value = text;
  listSuggestions([]);
  askGoal();
}

function askGoal() {
  // a new goal keeps the rest of the question
  const params = new URLSearchParams([["goal", $("goal").value.trim()]]);
  for (const [name, value] of address()) if (name !== "goal") params.append(name, value);
  if (!params.get("goal")) params.delete("goal");
  listSuggestions([]);
  navigate(params);
}

function moveSelection(step) {
  const items = [...$("suggestions").children];
  if (!items.length) return;
  const at = items.findIndex((li) => li.classList.contains("selected"));
  const next = (at + step + items.length) % items.length;
  items.forEach((li, k) => li.classList.toggle("selected", k === next));
  $("goal").setAttribute("aria-activedescendant", items[next].id);
}

// ------------------------------------------------------------------ start

function start() {
  try {
    info = JSON.parse($("info").textContent);
  } catch (e) {
    showError("the page came without what it offers: reload it");
  }
  $("data").textContent = info.data ? `data: ${info.data}` : "";
  const options = (blank) => [
    ...(blank ? [el("option", { value: "" }, "(nothing)")] : []),
    ...info.objectives.map((o) => el("option", { value: o }, o)),
  ];
  $("objective-1").replaceChildren(...options(false));
  $("objective-2").replaceChildren(...options(true));
  $("time-limit").placeholder = String(info.seconds);
  $("agents").placeholder = info.agents;

  $("ask").addEventListener("submit", (event) => {
    event.preventDefault();
    const selected = document.querySelector("#suggestions li.selected");
    if (selected) pick(selected.dataset.text);
    else askGoal();
  });
  $("goal").addEventListener("input", suggest);
  $("goal").addEventListener("focus", suggest);
  $("goal").addEventListener("keydown", (event) => {
    if (event.key === "ArrowDown") moveSelection(1);
    else if (event.key === "ArrowUp") moveSelection(-1);
    else if (event.key === "Escape") listSuggestions([]);
    else return;
    event.preventDefault();
  });
  $("suggestions").addEventListener("mousedown", (event) => {
    const item = event.target.closest("li");
    if (item) {
      event.preventDefault();
      pick(item.dataset.text);
    }
  });
  $("goal").addEventListener("blur", () => setTimeout(() => listSuggestions([]), 150));
  const changed = () => navigate(fromControls());
  $("question").addEventListener("change", (event) => {
    if (event.target.id !== "rule") changed();
  });
  $("question").addEventListener("submit", (event) => {
    event.preventDefault();
    changed();
  });
  $("schedule-form").addEventListener("submit", (event) => {
    event.preventDefault();
    changed();
  });
  $("cancel").addEventListener("click", () => {
    if (controller) controller.abort();
    controller = null;
    pending = 1;
    stopWorking();
    showError("cancelled: change the question, or reload the page to ask again");
  });
  for (const button of document.querySelectorAll("[data-export]")) {
    button.addEventListener("click", () => download(button.dataset.export));
  }
  window.addEventListener("popstate", show);
  show();
}

start();
