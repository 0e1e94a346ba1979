// owsim studio's web app (docs/studio.md): the scenario's YAML is the one state; every edit —
// a click on the map, a drag, a field, the segment sliders — changes keys of that document and
// asks the server what the loader makes of it: the map's view, or the loader's message beside
// the field it names. Save writes the document; Fly flies it.
import leafletCss from 'leaflet/dist/leaflet.css';
import css from './studio.css';
import * as api from './api.js';
import { Drawing } from './drawing.js';
import { FlyControl } from './fly.js';
import { ObjectForms, PLACES } from './object_forms.js';
import { drawCrossSection } from './cross_section.js';
import { drawProfile } from './profile.js';
import { ScenarioDoc, freshId, round } from './scenario_doc.js';
import { TrackMap } from './track_map.js';

const $ = (id) => document.getElementById(id);

function addStyle(text) {
  const style = document.createElement('style');
  style.textContent = text;
  document.head.append(style);
}

class Studio {
  async start() {
    addStyle(leafletCss);
    addStyle(css);
    const session = await api.session();
    $('scenario-name').textContent = session.scenario;
    this.doc = new ScenarioDoc(session.yaml);
    this.view = null;
    this.selected = null;
    this.map = new TrackMap($('map'));
    // The pointer's WGS-84 position, and its east/north in the scenario's frame converted exactly
    // by the server (one request in flight at a time; the latest position wins).
    let pointer = null;
    let asking = false;
    const readout = async () => {
      if (asking || !pointer || !this.view) return;
      asking = true;
      const latlng = pointer;
      pointer = null;
      const answer = await api.enu(this.view.origin, [[latlng.lat, latlng.lng]]);
      const at = `${latlng.lat.toFixed(6)}°, ${latlng.lng.toFixed(6)}°`;
      const [e, n] = answer.ok ? answer.points[0] : [NaN, NaN];
      $('cursor-coords').textContent = answer.ok ? `${at}  e ${e.toFixed(1)} m, n ${n.toFixed(1)} m` : at;
      asking = false;
      readout();
    };
    this.map.onPointer((latlng) => {
      pointer = latlng;
      readout();
    });
    this.forms = new ObjectForms($('object-list'), $('object-form'), {
      onEdit: (path, value) => this.edit(() => this.doc.set(path, value)),
      onDelete: (kind, index) => this.edit(() => {
        if (kind === 'forest') this.doc.remove(['scene', 'forest']);
        else this.doc.remove([...PLACES[kind].path, index]);
        this.selected = null;
      }),
      onPick: (kind, id) => this.pick(kind, id),
    });
    this.drawing = new Drawing(this.map.map, {
      span: (from, to) => this.addSpan(from, to),
      pole: (at) => this.addCylinder('pole', at),
      tree: (at) => this.addCylinder('tree', at),
      mesh: (at) => this.addMesh(at),
      forest: (corners) => this.addArea('forest', corners),
      fog: (corners) => this.addArea('fog', corners),
      moved: (kind, id, coordinates) => this.moved(kind, id, coordinates),
      selected: (kind, id) => this.pick(kind, id),
    });
    for (const button of document.querySelectorAll('#tools button')) {
      button.addEventListener('click', () => this.setTool(button.dataset.tool));
    }
    this.setTool('select');
    for (const id of ['seg-start', 'seg-end']) {
      $(id).addEventListener('change', () => this.segmentChanged());
      $(id).addEventListener('input', () => this.showSegmentOutputs());
    }
    $('cursor').addEventListener('input', () => this.cursorMoved());
    $('save').addEventListener('click', () => this.save());
    this.history = [];
    this.future = [];
    $('undo').addEventListener('click', () => this.undo());
    $('redo').addEventListener('click', () => this.redo());
    document.addEventListener('keydown', (event) => {
      if (!(event.ctrlKey || event.metaKey) || event.target.closest?.('input, select, textarea')) return;
      const key = event.key.toLowerCase();
      if (key === 'z' && !event.shiftKey) this.undo();
      else if (key === 'y' || (key === 'z' && event.shiftKey)) this.redo();
      else return;
      event.preventDefault();
    });
    this.fly = new FlyControl({
      flyButton: $('fly'),
      cancelButton: $('cancel'),
      progress: $('progress'),
      status: $('status'),
      reportPane: $('report-pane'),
      reportFrame: $('report'),
      closeButton: $('close-report'),
      yaml: () => this.doc.text(),
      onProblem: (problem) => this.showProblem(problem),
    });
    this.listenToReport();
    const models = await api.models();
    this.forms.models = models.files ?? [];
    for (const file of this.forms.models) $('mesh-file').append(new Option(file, file));
    $('mesh-file').hidden = this.forms.models.length === 0;
    document.querySelector('#tools button[data-tool="mesh"]').disabled = this.forms.models.length === 0;
    await this.refresh();
    document.body.dataset.ready = 'true';
  }

  setTool(tool) {
    for (const button of document.querySelectorAll('#tools button')) {
      button.classList.toggle('active', button.dataset.tool === tool);
    }
    this.drawing.setTool(tool);
  }

  // Applies `change` to the document, then asks the loader; the change stays (so the user can
  // mend it) and its problem is shown.
  async edit(change) {
    change();
    await this.refresh();
  }

  // Every state of the document in order, for Undo and Redo (texts: a state is the YAML).
  recordHistory() {
    const text = this.doc.text();
    if (this.history.at(-1) === text) return;
    this.history.push(text);
    this.future = [];
  }

  async undo() {
    if (this.history.length < 2) return;
    this.future.push(this.history.pop());
    this.doc = new ScenarioDoc(this.history.at(-1));
    await this.refresh();
  }

  async redo() {
    if (this.future.length === 0) return;
    const text = this.future.pop();
    this.history.push(text);
    this.doc = new ScenarioDoc(text);
    await this.refresh();
  }

  async refresh() {
    this.recordHistory();
    $('undo').disabled = this.history.length < 2;
    $('redo').disabled = this.future.length === 0;
    const answer = await api.view(this.doc.text());
    this.forms.showList(this.doc);
    if (this.selected) this.forms.showForm(this.doc, this.selected.kind, this.selected.id);
    if (!answer.ok) {
      this.showProblem(answer.problem);
      return false;
    }
    this.showProblem(null);
    this.view = answer.view;
    this.setupSliders();
    this.map.show(this.view, this.segment());
    this.drawing.showHandles({ ...this.view.handles, meshes: this.meshHandles() });
    this.cursorMoved();
    this.showSection();
    return true;
  }

  showProblem(problem) {
    const besideField = problem ? this.forms.showProblem(problem) : this.forms.showProblem(null);
    $('problem').textContent = problem && !besideField ? problem.message : '';
    if (problem && besideField) $('problem').textContent = '';
    document.body.dataset.problem = problem ? problem.message : '';
  }

  // The trajectory's start_s and duration_s as the segment [start, end] in seconds.
  segment() {
    const start = Number(this.doc.get(['trajectory', 'start_s']) ?? this.view?.track.start_s ?? 0);
    const duration = this.doc.get(['trajectory', 'duration_s']);
    const end = duration === undefined || duration === null
      ? this.view?.track.end_s ?? start
      : start + Number(duration);
    return { start, end };
  }

  setupSliders() {
    const track = this.view.track;
    const { start, end } = this.segment();
    for (const id of ['seg-start', 'seg-end', 'cursor']) {
      $(id).min = track.start_s;
      $(id).max = track.end_s;
    }
    $('seg-start').value = start;
    $('seg-end').value = end;
    if ($('cursor').dataset.touched !== 'true') $('cursor').value = start;
    this.showSegmentOutputs();
  }

  showSegmentOutputs() {
    $('seg-start-out').textContent = Number($('seg-start').value).toFixed(1);
    $('seg-end-out').textContent = Number($('seg-end').value).toFixed(1);
  }

  async segmentChanged() {
    let start = Number($('seg-start').value);
    let end = Number($('seg-end').value);
    if (end < start) [start, end] = [end, start];
    await this.edit(() => {
      this.doc.set(['trajectory', 'start_s'], round(start, 3));
      this.doc.set(['trajectory', 'duration_s'], round(end - start, 3));
    });
  }

  cursorMoved() {
    if (!this.view) return;
    const t = Number($('cursor').value);
    $('cursor').dataset.touched = 'true';
    $('cursor-out').textContent = t.toFixed(2);
    const track = this.view.track;
    let k = 0;
    while (k + 1 < track.t.length && track.t[k + 1] <= t) k += 1;
    this.map.showCursor(k);
    drawProfile($('profile'), track, this.segment(), t);
  }

  pick(kind, id) {
    this.selected = { kind, id };
    this.forms.showForm(this.doc, kind, id);
    this.map.highlight(id);
    this.showSection();
  }

  // The selected span's cross-section against the ground, under its form.
  showSection() {
    const canvas = $('cross-section');
    const span = this.selected?.kind === 'span'
      ? this.view?.handles.spans.find((s) => s.id === this.selected.id)
      : null;
    canvas.hidden = !span;
    drawCrossSection(canvas, span?.section);
  }

  // A click on a row of the report's ground-truth table (in its frame) picks that object here.
  listenToReport() {
    window.addEventListener('message', (event) => {
      if (event.origin !== window.location.origin || typeof event.data?.owsimObject !== 'string') return;
      const id = event.data.owsimObject;
      const kinds = { span: this.view?.handles.spans, pole: this.view?.handles.poles, tree: this.view?.handles.trees };
      // A conductor "<span>/<n>" or a span's support "<span>/pole-1" belongs to its span.
      const owner = id.includes('/') ? id.slice(0, id.indexOf('/')) : id;
      for (const [kind, list] of Object.entries(kinds)) {
        if (list?.some((item) => item.id === owner)) {
          $('report-pane').hidden = true;
          this.pick(kind, owner);
          this.map.highlight(id);
          return;
        }
      }
      this.map.highlight(id);
      $('report-pane').hidden = true;
    });
  }

  async addSpan(from, to) {
    const id = freshId(this.doc, PLACES.span.path, 'span');
    this.doc.append(PLACES.span.path, {
      id,
      from: { lat: round(from[0], 8), lon: round(from[1], 8) },
      to: { lat: round(to[0], 8), lon: round(to[1], 8) },
      support_heights_m: [30, 30],
      lowest_point_m: 20,
      layout: 'single',
      conductor: { diameter_mm: 20, reflectivity: 0.4 },
      supports: { kind: 'pole', diameter_m: 0.5, reflectivity: 0.3 },
    });
    this.selected = { kind: 'span', id };
    this.setTool('select');
    await this.refresh();
  }

  async addCylinder(kind, at) {
    const id = freshId(this.doc, PLACES[kind].path, kind);
    const size = kind === 'pole'
      ? { height_m: 25, diameter_m: 0.4, reflectivity: 0.3 }
      : { height_m: 15, diameter_m: 4, reflectivity: 0.2 };
    this.doc.append(PLACES[kind].path, { id, at: { lat: round(at[0], 8), lon: round(at[1], 8) }, ...size });
    this.selected = { kind, id };
    await this.refresh();
  }

  // A model file of the scenario's folder (the one chosen beside the Mesh tool), its origin where
  // the user clicked, on the ground.
  async addMesh(at) {
    const file = $('mesh-file').value;
    if (!file) return;
    const id = freshId(this.doc, PLACES.mesh.path, 'mesh');
    this.doc.append(PLACES.mesh.path, {
      id, file, at: { lat: round(at[0], 8), lon: round(at[1], 8) }, yaw_deg: 0, scale: 1, class: 'building', reflectivity: 0.3,
    });
    this.selected = { kind: 'mesh', id };
    this.setTool('select');
    await this.refresh();
  }

  // The meshes whose origin the scenario gives as {lat, lon}: their handles (a mesh given in
  // metres or UTM is moved in the YAML).
  meshHandles() {
    return this.doc.list(PLACES.mesh.path)
      .filter((mesh) => Number.isFinite(mesh?.at?.lat) && Number.isFinite(mesh?.at?.lon))
      .map((mesh) => ({ id: mesh.id, at: [mesh.at.lat, mesh.at.lon] }));
  }

  // The east and north ranges ([min, max], 0.1 m) that hold WGS-84 corners, converted exactly by
  // the server in the scenario's frame; null (the problem shown) when it cannot.
  async eastNorthRanges(corners) {
    if (!this.view) return null;
    const answer = await api.enu(this.view.origin, corners);
    if (!answer.ok) {
      this.showProblem(answer.problem);
      return null;
    }
    const range = (values) => [round(Math.min(...values), 1), round(Math.max(...values), 1)];
    return { e: range(answer.points.map((p) => p[0])), n: range(answer.points.map((p) => p[1])) };
  }

  // A forest area or a fog box from a rectangle's corners, as east/north ranges (the keys take
  // metres): converted exactly by the server in the scenario's local frame.
  async addArea(kind, corners) {
    const ranges = await this.eastNorthRanges(corners);
    if (!ranges) return;
    const { e, n } = ranges;
    if (kind === 'forest') {
      this.doc.set(['scene', 'forest'], {
        count: 200, area: { e, n }, height_m: [8, 25], diameter_m: [2, 8], reflectivity: 0.2,
      });
      this.selected = { kind: 'forest', id: 'forest' };
    } else {
      const id = freshId(this.doc, PLACES.fog.path, 'fog');
      this.doc.append(PLACES.fog.path, { id, visibility_m: 300, box: { e, n, u: [-50, 300] } });
      this.selected = { kind: 'fog', id };
    }
    this.setTool('select');
    await this.refresh();
  }

  async moved(kind, id, coordinates) {
    if (kind === 'forest' || kind === 'fog') {
      await this.movedArea(kind, id, coordinates);
      return;
    }
    const index = this.doc.list(PLACES[kind].path).findIndex((item) => item?.id === id);
    if (index < 0) return;
    const base = [...PLACES[kind].path, index];
    await this.edit(() => {
      if (kind === 'span') {
        this.doc.setPosition([...base, 'from'], coordinates[0]);
        this.doc.setPosition([...base, 'to'], coordinates[coordinates.length - 1]);
      } else {
        this.doc.setPosition([...base, 'at'], coordinates[0]);
      }
    });
  }

  // A forest's area or a fog box dragged: its new corners as east/north ranges (exact, by the
  // server), the box's heights kept.
  async movedArea(kind, id, corners) {
    const ranges = await this.eastNorthRanges(corners);
    if (!ranges) return;
    const { e, n } = ranges;
    await this.edit(() => {
      if (kind === 'forest') {
        this.doc.set(['scene', 'forest', 'area', 'e'], e);
        this.doc.set(['scene', 'forest', 'area', 'n'], n);
      } else {
        const index = this.doc.list(PLACES.fog.path).findIndex((item) => item?.id === id);
        if (index < 0) return;
        this.doc.set([...PLACES.fog.path, index, 'box', 'e'], e);
        this.doc.set([...PLACES.fog.path, index, 'box', 'n'], n);
      }
    });
  }

  async save() {
    const answer = await api.save(this.doc.text());
    if (!answer.ok) {
      this.showProblem(answer.problem);
      return;
    }
    $('status').textContent = `saved ${answer.saved}`;
  }
}

const studio = new Studio();
window.owsimStudio = studio;  // for the browser test (tests/web/studio_flow.mjs)
studio.start().catch((error) => {
  $('problem').textContent = `studio: ${error.message}`;
});
