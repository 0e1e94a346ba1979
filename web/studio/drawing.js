// The editing gestures, by terra-draw (its Leaflet adapter): a span by two clicks (its two
// supports), a pole, a tree or a mesh (its origin) by one, a forest or a fog box by a rectangle;
// spans' supports, poles, trees, meshes (by their origin), the forest and fog boxes dragged in
// select mode. What is drawn here are handles: the objects themselves
// are drawn from the server's view of the scenario (track_map.js), so the map shows what
// `owsim run` builds.
import L from 'leaflet';
import {
  TerraDraw,
  TerraDrawLineStringMode,
  TerraDrawPointMode,
  TerraDrawRectangleMode,
  TerraDrawSelectMode,
} from 'terra-draw';
import { TerraDrawLeafletAdapter } from 'terra-draw-leaflet-adapter';

let nextId = 0;
const idStrategy = {
  isValidId: (id) => typeof id === 'string' && id.length > 0,
  getId: () => `draft-${(nextId += 1)}`,
};

export class Drawing {
  // handlers: {span(from, to), pole(at), tree(at), mesh(at), forest(corners), fog(corners),
  //            moved(kind, id, coordinates), selected(kind, id)}
  constructor(map, handlers) {
    this.handlers = handlers;
    this.pending = null;
    const point = (name, colour) =>
      new TerraDrawPointMode({ modeName: name, styles: { pointColor: colour, pointWidth: 6 } });
    this.draw = new TerraDraw({
      adapter: new TerraDrawLeafletAdapter({ lib: L, map }),
      idStrategy,
      modes: [
        point('span', '#c0392b'),
        point('pole', '#6e4b2a'),
        point('tree', '#2e7d32'),
        point('mesh', '#555555'),
        new TerraDrawRectangleMode({ modeName: 'forest' }),
        new TerraDrawRectangleMode({ modeName: 'fog' }),
        new TerraDrawLineStringMode({ modeName: 'span-line', styles: { lineStringColor: '#c0392b', lineStringWidth: 3 } }),
        point('pole-handle', '#6e4b2a'),
        point('tree-handle', '#2e7d32'),
        point('mesh-handle', '#555555'),
        new TerraDrawRectangleMode({ modeName: 'area-handle', styles: { fillColor: '#2e7d32', fillOpacity: 0.08, outlineColor: '#2e7d32', outlineWidth: 1 } }),
        new TerraDrawSelectMode({
          flags: {
            'span-line': { feature: { draggable: true, coordinates: { draggable: true } } },
            'pole-handle': { feature: { draggable: true } },
            'tree-handle': { feature: { draggable: true } },
            'mesh-handle': { feature: { draggable: true } },
            'area-handle': { feature: { draggable: true } },
          },
        }),
      ],
    });
    this.draw.start();
    this.draw.on('finish', (id, context) => this.finished(id, context));
    this.draw.on('select', (id) => {
      const feature = this.draw.getSnapshotFeature(id);
      if (feature?.properties.object) this.handlers.selected(feature.properties.kind, feature.properties.object);
    });
  }

  setTool(tool) {
    this.pending = null;
    this.removeDrafts();
    this.draw.setMode(tool === 'select' ? 'select' : tool);
  }

  removeDrafts() {
    const drafts = this.draw.getSnapshot().filter((f) => !f.properties.object).map((f) => f.id);
    if (drafts.length > 0) this.draw.removeFeatures(drafts);
  }

  finished(id, context) {
    const feature = this.draw.getSnapshotFeature(id);
    if (!feature) return;
    const mode = feature.properties.mode;
    const latLon = ([lon, lat]) => [lat, lon];
    if (context?.action === 'draw') {
      if (mode === 'span') {
        const at = latLon(feature.geometry.coordinates);
        if (this.pending === null) {
          this.pending = at;  // the first support; the second click makes the span
          return;
        }
        const from = this.pending;
        this.pending = null;
        this.removeDrafts();
        this.handlers.span(from, at);
      } else if (mode === 'pole' || mode === 'tree' || mode === 'mesh') {
        this.removeDrafts();
        this.handlers[mode](latLon(feature.geometry.coordinates));
      } else if (mode === 'forest' || mode === 'fog') {
        const corners = feature.geometry.coordinates[0].map(latLon);
        this.removeDrafts();
        this.handlers[mode](corners);
      }
      return;
    }
    // A drag in select mode ended: the handle's new place.
    if (feature.properties.object) {
      const geometry = feature.geometry;
      const coordinates = geometry.type === 'Point'
        ? [latLon(geometry.coordinates)]
        : geometry.type === 'Polygon'
          ? geometry.coordinates[0].map(latLon)
          : geometry.coordinates.map(latLon);
      this.handlers.moved(feature.properties.kind, feature.properties.object, coordinates);
    }
  }

  // The draggable handles of the scenario's spans, poles, trees, meshes, forest and fog boxes.
  showHandles(handles) {
    const mode = this.draw.getMode();
    this.draw.clear();
    const lonLat = ([lat, lon]) => [lon, lat];
    const features = [];
    for (const span of handles.spans) {
      features.push({
        id: `span:${span.id}`,
        type: 'Feature',
        geometry: { type: 'LineString', coordinates: [lonLat(span.from), lonLat(span.to)] },
        properties: { mode: 'span-line', kind: 'span', object: span.id },
      });
    }
    for (const [kind, list] of [['pole', handles.poles], ['tree', handles.trees], ['mesh', handles.meshes ?? []]]) {
      for (const item of list) {
        features.push({
          id: `${kind}:${item.id}`,
          type: 'Feature',
          geometry: { type: 'Point', coordinates: lonLat(item.at) },
          properties: { mode: `${kind}-handle`, kind, object: item.id },
        });
      }
    }
    const lonLatRing = (corners) => [...corners, corners[0]].map(lonLat);
    for (const area of handles.areas ?? []) {
      features.push({
        id: `${area.kind}:${area.id}`,
        type: 'Feature',
        geometry: { type: 'Polygon', coordinates: [lonLatRing(area.corners)] },
        properties: { mode: 'area-handle', kind: area.kind, object: area.id },
      });
    }
    const results = this.draw.addFeatures(features);
    const refused = results.filter((r) => !r.valid);
    if (refused.length > 0) console.warn('studio: handles not drawn', refused);
    if (mode) this.draw.setMode(mode);
  }
}
