// viewray's live playground, beside its four parts: the lecture's catalogue of mistakes
// (compiled into the page by the server, each entry with the camera families it can be
// made in). The menu offers the entries that fit the current camera; the ones chosen go
// with every request, so the picture, the views and the numbers are the camera a student
// with those mistakes wrote; a label over the picture names each with its lecture line.

// The family of camera a projection kind is: a preset is one of the families.
const PRESET_FAMILIES = {
  Front: "Orthographic", Top: "Orthographic", Side: "Orthographic", Isometric: "Orthographic",
  Dimetric: "Orthographic", Trimetric: "Orthographic", Cavalier: "Oblique", Cabinet: "Oblique",
  OnePoint: "Perspective", TwoPoint: "Perspective", ThreePoint: "Perspective",
};

// The family of the camera being edited; null when the page cannot read it (the server
// then says which mistakes it refuses).
function cameraFamily() {
  const kind = kindOf(model);
  if (kind === null) return null;
  return PRESET_FAMILIES[kind] || kind;
}

function entryOf(id) {
  return served.catalogue.find((entry) => entry.id === id);
}

// Whether the catalogue's entry fits the current camera (any, when its family is not
// known).
function fitsCamera(entry) {
  const family = cameraFamily();
  return family === null || entry.families.includes(family);
}

function chosenMistakes() {
  return state.mistakes ? state.mistakes.split(",") : [];
}

// Drops the chosen mistakes the current camera cannot make (after its kind changed).
function dropUnfittingMistakes() {
  state.mistakes = chosenMistakes().filter((id) => fitsCamera(entryOf(id))).join(",");
}

// Whether a chosen mistake moves the picture sideways (the top view shows it).
function sidewaysMistake() {
  return chosenMistakes().some((id) => entryOf(id).sideways);
}

// The menu: a checkbox for each entry that fits the camera, in the catalogue's order.
function buildMistakes() {
  const list = $("mistakes-list");
  list.replaceChildren();
  const chosen = chosenMistakes();
  const family = cameraFamily();
  let offered = 0;
  for (const entry of served.catalogue) {
    if (!fitsCamera(entry)) continue;
    offered += 1;
    const label = document.createElement("label");
    label.className = "mistake";
    label.title = `${entry.summary}: ${entry.mistaken}. ${entry.picture}. The lecture: ${entry.fix}`;
    const box = document.createElement("input");
    box.type = "checkbox";
    box.value = entry.id;
    box.checked = chosen.includes(entry.id);
    box.addEventListener("change", chooseMistakes);
    const id = document.createElement("code");
    id.textContent = entry.id;
    const looks = document.createElement("span");
    looks.className = "looks";
    looks.textContent = entry.looks;
    label.append(box, id, looks);
    list.append(label);
  }
  const left = served.catalogue.length - offered;
  const note = document.createElement("p");
  note.className = "note";
  note.textContent = offered === 0
    ? `No mistake of the catalogue can be made in a ${family} camera.`
    : left > 0 ? `${left} more fit other kinds of camera.` : "";
  list.append(note);
  const count = chosen.length;
  $("mistakes-summary").textContent = count ? `Mistakes (${count})` : "Mistakes";
  $("mistakes-menu").classList.toggle("on", count > 0);
  showMistakeLabel();
}

function chooseMistakes() {
  lastCameraControl = "mistakes";
  const ticked = [...document.querySelectorAll("#mistakes-list input:checked")].map((box) => box.value);
  state.mistakes = mistakesOf(ticked.join(","));
  buildMistakes();
  commit("full");
}

// The label over the picture: each mistake made, in a few words, and the lecture's line
// it breaks (the mistaken formula is in the menu entry's title).
function showMistakeLabel() {
  const label = $("mistake-label");
  label.replaceChildren();
  const chosen = chosenMistakes();
  label.hidden = chosen.length === 0;
  for (const id of chosen) {
    const entry = entryOf(id);
    const line = document.createElement("div");
    const name = document.createElement("b");
    name.textContent = entry.id;
    const right = document.createElement("code");
    right.textContent = entry.fix;
    line.append(name, ` ${entry.summary}; the lecture: `, right);
    label.append(line);
  }
}
