// The offline map: no tile server — the ground's hillshade and contours (a DEM or height grid),
// the track coloured by time, the selected segment, the scene's objects as built (wires, poles,
// trees, mesh and fog outlines), the aircraft and its field of view at the time cursor, a scale
// and a north arrow; the pointer's position goes to the studio's readout.
import L from 'leaflet';
import { terrainLayer } from './terrain_layer.js';

// A colour for position s ∈ [0, 1] along the flight (blue → green → yellow).
export function timeColour(s) {
  const stops = [[49, 54, 149], [69, 117, 180], [116, 173, 209], [171, 217, 233], [254, 224, 144], [253, 174, 97]];
  const x = Math.min(1, Math.max(0, s)) * (stops.length - 1);
  const k = Math.min(stops.length - 2, Math.floor(x));
  const f = x - k;
  const c = stops[k].map((v, i) => Math.round(v + f * (stops[k + 1][i] - v)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

const CLASS_COLOURS = { wire: '#c0392b', pole: '#6e4b2a', tree: '#2e7d32', building: '#555', fog: '#7f8c8d' };

export class TrackMap {
  constructor(element) {
    this.map = L.map(element, { zoomSnap: 0.25, attributionControl: false, preferCanvas: false });
    this.map.setView([0, 0], 2);
    L.control.scale({ metric: true, imperial: false }).addTo(this.map);
    const North = L.Control.extend({
      onAdd() {
        const div = L.DomUtil.create('div', 'north-arrow');
        div.textContent = 'N ↑';
        div.title = 'north is up';
        return div;
      },
    });
    new North({ position: 'topright' }).addTo(this.map);
    this.terrainLayer = L.layerGroup().addTo(this.map);
    this.trackLayer = L.layerGroup().addTo(this.map);
    this.objectLayer = L.layerGroup().addTo(this.map);
    this.cursorLayer = L.layerGroup().addTo(this.map);
    this.fitted = false;
  }

  onPointer(callback) {
    this.map.on('mousemove', (event) => callback(event.latlng));
  }

  show(view, segment) {
    this.view = view;
    this.trackLayer.clearLayers();
    this.objectLayer.clearLayers();
    // The ground changes only with the scenario's terrain: redrawn when its lattice does.
    const terrainKey = JSON.stringify(view.terrain?.bounds ?? null) + (view.terrain?.heights.length ?? 0);
    if (terrainKey !== this.terrainKey) {
      this.terrainKey = terrainKey;
      this.terrainLayer.clearLayers();
      this.terrainLayer.addLayer(terrainLayer(view.terrain));
    }
    const track = view.track;
    const count = track.t.length;
    const span = Math.max(1e-9, track.end_s - track.start_s);
    for (let k = 0; k + 1 < count; k += 1) {
      const inSegment = track.t[k] >= segment.start && track.t[k + 1] <= segment.end;
      L.polyline([track.points[k], track.points[k + 1]], {
        color: timeColour((track.t[k] - track.start_s) / span),
        weight: inSegment ? 6 : 2,
        opacity: inSegment ? 1 : 0.7,
        interactive: false,
      }).addTo(this.trackLayer);
    }
    for (const object of view.objects) this.drawObject(object);
    if (!this.fitted && count > 0) {
      this.map.fitBounds(L.latLngBounds(track.points), { padding: [20, 20] });
      this.fitted = true;
    }
  }

  // Objects are drawn, not grabbed: the pointer belongs to the drawing gestures (terra-draw's
  // handles), so these layers take no events; their ids are kept for highlight().
  drawObject(object) {
    const colour = CLASS_COLOURS[object.class] ?? '#8e44ad';
    const style = { color: colour, interactive: false, objectId: object.id };
    if (object.line) {
      L.polyline(object.line, { ...style, weight: 2 }).addTo(this.objectLayer);
    } else if (object.at) {
      L.circle(object.at, { ...style, radius: Math.max(object.radius_m, 0.5), weight: 2 }).addTo(this.objectLayer);
    } else if (object.outline) {
      L.polygon(object.outline, { ...style, weight: 1, fillOpacity: 0.1 }).addTo(this.objectLayer);
    }
  }

  // The aircraft and the sensor's field at track sample k.
  showCursor(k) {
    this.cursorLayer.clearLayers();
    const track = this.view?.track;
    if (!track || k < 0 || k >= track.t.length) return;
    L.polygon(track.fov[k], { color: '#e67e22', weight: 1, fillOpacity: 0.15, interactive: false }).addTo(this.cursorLayer);
    L.circleMarker(track.points[k], { radius: 6, color: '#000', fillColor: '#f1c40f', fillOpacity: 1, interactive: false }).addTo(this.cursorLayer);
  }

  highlight(id) {
    this.objectLayer.eachLayer((layer) => {
      const objectId = layer.options.objectId ?? '';
      const hit = objectId === id || objectId.startsWith(`${id}/`);
      if (layer.setStyle) layer.setStyle({ weight: hit ? 5 : 2 });
    });
  }
}
