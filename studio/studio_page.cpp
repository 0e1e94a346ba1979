#include "studio/studio_page.hpp"

namespace owsim::studio {

std::string_view studio_page_html() {
  return R"(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>owsim studio</title>
<link rel="icon" href="data:,">
</head>
<body>
<header id="bar">
  <strong>owsim studio</strong>
  <span id="scenario-name"></span>
  <span id="status" role="status"></span>
  <span class="spacer"></span>
  <button id="undo" type="button" title="Ctrl+Z">Undo</button>
  <button id="redo" type="button" title="Ctrl+Shift+Z or Ctrl+Y">Redo</button>
  <button id="save" type="button">Save</button>
  <button id="fly" type="button">Fly</button>
  <button id="cancel" type="button" hidden>Cancel</button>
  <progress id="progress" max="1" value="0" hidden></progress>
</header>
<main>
  <section id="map-pane">
    <div id="map"></div>
    <div id="tools" role="toolbar">
      <button type="button" data-tool="select">Select</button>
      <button type="button" data-tool="span">Span</button>
      <button type="button" data-tool="pole">Pole</button>
      <button type="button" data-tool="tree">Tree</button>
      <button type="button" data-tool="mesh">Mesh</button>
      <select id="mesh-file" title="the model file the Mesh tool places"></select>
      <button type="button" data-tool="forest">Forest</button>
      <button type="button" data-tool="fog">Fog</button>
      <span id="cursor-coords"></span>
    </div>
  </section>
  <aside id="side">
    <section id="flight">
      <h2>Flight</h2>
      <canvas id="profile" width="420" height="140"></canvas>
      <label>Segment start <input id="seg-start" type="range" step="0.5"> <output id="seg-start-out"></output> s</label>
      <label>Segment end <input id="seg-end" type="range" step="0.5"> <output id="seg-end-out"></output> s</label>
      <label>Time cursor <input id="cursor" type="range" step="0.25"> <output id="cursor-out"></output> s</label>
    </section>
    <section id="objects">
      <h2>Objects</h2>
      <ul id="object-list"></ul>
      <div id="object-form"></div>
      <canvas id="cross-section" width="420" height="120" hidden></canvas>
    </section>
    <section id="problems"><p id="problem" role="alert"></p></section>
  </aside>
</main>
<section id="report-pane" hidden>
  <header><strong>Report</strong> <button id="close-report" type="button">Back to the map</button></header>
  <iframe id="report" title="report"></iframe>
</section>
<script src="/studio.js"></script>
</body>
</html>
)";
}

}  // namespace owsim::studio
