// viewray's live playground, part 1 of 4: a small reader and writer for RON camera
// values (numbers, identifiers, strings, tuples and structs, named or not, lists and
// maps, comments), and the helpers that edit a camera's tree. The page's four scripts
// are put together in one <script> (ron.js, live.js, page.js, presenter.js).
"use strict";

class RonError extends Error {
  constructor(message, offset, text) {
    const before = text.slice(0, offset);
    const line = before.split("\n").length;
    const column = offset - before.lastIndexOf("\n");
    super(`camera:${line}:${column}: ${message}`);
  }
}

function parseRon(text) {
  let i = 0;
  const fail = (message) => { throw new RonError(message, i, text); };
  const skip = () => {
    for (;;) {
      while (i < text.length && /\s/.test(text[i])) i++;
      if (text.startsWith("//", i)) {
        const end = text.indexOf("\n", i);
        i = end < 0 ? text.length : end + 1;
      } else if (text.startsWith("/*", i)) {
        const end = text.indexOf("*/", i + 2);
        if (end < 0) fail("unterminated comment");
        i = end + 2;
      } else return;
    }
  };
  const peek = () => { skip(); return text[i]; };
  const expect = (c) => { if (peek() !== c) fail(`expected \`${c}\``); i++; };
  const ident = () => {
    skip();
    const m = /^[A-Za-z_][A-Za-z0-9_]*/.exec(text.slice(i));
    if (!m) fail("expected a name");
    i += m[0].length;
    return m[0];
  };
  const isFieldStart = () => {
    skip();
    const m = /^[A-Za-z_][A-Za-z0-9_]*\s*:(?!:)/.exec(text.slice(i));
    return m !== null;
  };
  const inner = (name, close) => {
    // After `(`: a struct's fields or a tuple's items.
    if (isFieldStart()) {
      const fields = [];
      while (peek() !== close) {
        const key = ident();
        expect(":");
        fields.push({ key, value: value() });
        if (peek() === ",") i++; else break;
      }
      expect(close);
      return { kind: "struct", name, fields };
    }
    const items = [];
    while (peek() !== close) {
      items.push(value());
      if (peek() === ",") i++; else break;
    }
    expect(close);
    return { kind: "tuple", name, items };
  };
  const value = () => {
    const c = peek();
    if (c === undefined) fail("unexpected end of the camera");
    if (c === "(") { i++; return inner(null, ")"); }
    if (c === "[") {
      i++;
      const items = [];
      while (peek() !== "]") { items.push(value()); if (peek() === ",") i++; else break; }
      expect("]");
      return { kind: "list", items };
    }
    if (c === "{") {
      i++;
      const entries = [];
      while (peek() !== "}") {
        const key = value(); expect(":"); entries.push({ key, value: value() });
        if (peek() === ",") i++; else break;
      }
      expect("}");
      return { kind: "map", entries };
    }
    if (c === '"') {
      const m = /^"(?:[^"\\]|\\.)*"/.exec(text.slice(i));
      if (!m) fail("unterminated string");
      i += m[0].length;
      return { kind: "str", text: m[0] };
    }
    const number = /^[+-]?(?:\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?|inf|NaN)/.exec(text.slice(i));
    if (number && /[-+.\d]/.test(c) || (number && /^(inf|NaN)$/.test(number[0]))) {
      i += number[0].length;
      return { kind: "num", value: Number(number[0].replace("inf", "Infinity")), text: number[0] };
    }
    const name = ident();
    if (peek() === "(") { i++; return inner(name, ")"); }
    return { kind: "ident", name };
  };
  const result = value();
  if (peek() !== undefined) fail("unexpected text after the camera");
  return result;
}

function formatNumber(x) {
  if (!Number.isFinite(x)) return String(x);
  let s = String(Math.round(x * 1e6) / 1e6);
  if (s.includes("e")) s = x.toFixed(9).replace(/0+$/, "");
  if (s === "-0") s = "0";
  return /[.]/.test(s) ? s : s + ".0";
}

function writeRon(node, pretty) {
  const w = (n) => writeRon(n, false);
  switch (node.kind) {
    case "num": return node.text !== undefined ? node.text : formatNumber(node.value);
    case "ident": return node.name;
    case "str": return node.text;
    case "list": return `[${node.items.map(w).join(", ")}]`;
    case "map": return `{${node.entries.map((e) => `${w(e.key)}: ${w(e.value)}`).join(", ")}}`;
    case "tuple": return `${node.name || ""}(${node.items.map(w).join(", ")})`;
    case "struct": {
      const fields = node.fields.map((f) => `${f.key}: ${w(f.value)}`);
      if (pretty && !node.name) return `(\n    ${fields.join(",\n    ")},\n)`;
      return `${node.name || ""}(${fields.join(", ")})`;
    }
  }
  return "";
}

const num = (value) => ({ kind: "num", value });
const vec = (values) => ({ kind: "tuple", name: null, items: values.map(num) });

function field(node, key) {
  if (!node || node.kind !== "struct") return undefined;
  const f = node.fields.find((f) => f.key === key);
  return f && f.value;
}
function setField(node, key, value, after) {
  const f = node.fields.find((f) => f.key === key);
  if (f) { f.value = value; return; }
  let at = node.fields.length;
  if (after) {
    const k = node.fields.findIndex((f) => f.key === after);
    if (k >= 0) at = k + 1;
  }
  node.fields.splice(at, 0, { key, value });
}
function removeField(node, key) {
  node.fields = node.fields.filter((f) => f.key !== key);
}
function numberOf(node, fallback) {
  return node && node.kind === "num" ? node.value : fallback;
}
function vecOf(node, fallback) {
  if (node && node.kind === "tuple" && node.items.every((n) => n.kind === "num")) {
    return node.items.map((n) => n.value);
  }
  return fallback;
}
