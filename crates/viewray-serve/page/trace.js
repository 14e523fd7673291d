// viewray's live playground, beside its four parts: the chosen pixel's trace, as
// `viewray trace` prints it (the lecture's pseudocode for the pixel of a one-sample
// render, every number beside its formula), in its own panel. The text is the server's,
// from the code the command line prints it with; this part only asks for it and shows it.

const traceChannel = new Channel((job, response, body, superseded) => {
  // The ray's request shows a pixel's error; a trace asked for before a mistake was made is
  // not shown.
  if (!response.ok || superseded || state.mistakes) return;
  const [row, col] = job.meta.pixel;
  $("trace-title").textContent = `as viewray trace SCENE --pixel ${row},${col} prints it`;
  $("trace").textContent = body;
  $("trace-box").hidden = false;
});
channels.push(traceChannel);

// Asks for the chosen pixel's trace through the current camera, size and shading (none
// without a chosen pixel).
function requestTrace() {
  if (!state.pixel) { $("trace-box").hidden = true; return; }
  if (state.mistakes) {
    // The trace prints the lecture's formulas with their numbers; a mistaken camera
    // follows other formulas.
    $("trace-title").textContent = "not for a mistaken camera";
    $("trace").textContent = "The trace follows the lecture's formulas, which a camera with the "
      + "catalogue's mistakes does not: untick them (M) to trace this pixel.";
    $("trace-box").hidden = false;
    return;
  }
  const [row, col] = state.pixel;
  const query = cameraQuery({ shading: state.shading, row, col, format: "text" });
  traceChannel.send(`/api/trace?${query}`, { pixel: state.pixel });
}
