// The object list and one form per object, each field a scenario key (INTERFACE.md "Scenario
// file"): editing a field sets that key in the YAML document; the loader's verdict comes back
// beside the field its key names.

// Fields per kind: [label, path below the object, type, extra].
const FIELDS = {
  span: [
    ['id', ['id'], 'text'],
    ['support 1 height (m)', ['support_heights_m', 0], 'number'],
    ['support 2 height (m)', ['support_heights_m', 1], 'number'],
    ['lowest point (m)', ['lowest_point_m'], 'number'],
    ['layout', ['layout'], 'select', ['single', 'tri', 'sept']],
    ['conductor diameter (mm)', ['conductor', 'diameter_mm'], 'number'],
    ['conductor reflectivity', ['conductor', 'reflectivity'], 'number'],
    ['supports', ['supports', 'kind'], 'select', ['pole', 'none']],
  ],
  pole: [
    ['id', ['id'], 'text'],
    ['height (m)', ['height_m'], 'number'],
    ['diameter (m)', ['diameter_m'], 'number'],
    ['reflectivity', ['reflectivity'], 'number'],
  ],
  forest: [
    ['count', ['count'], 'number'],
    ['lowest height (m)', ['height_m', 0], 'number'],
    ['highest height (m)', ['height_m', 1], 'number'],
    ['smallest diameter (m)', ['diameter_m', 0], 'number'],
    ['largest diameter (m)', ['diameter_m', 1], 'number'],
  ],
  fog: [
    ['id', ['id'], 'text'],
    ['visibility (m)', ['visibility_m'], 'number'],
  ],
  mesh: [
    ['id', ['id'], 'text'],
    ['file', ['file'], 'model'],
    ['yaw (° from north)', ['yaw_deg'], 'number'],
    ['scale', ['scale'], 'number'],
    ['class', ['class'], 'select', ['building', 'pole', 'tree']],
    ['reflectivity', ['reflectivity'], 'number'],
  ],
};
FIELDS.tree = FIELDS.pole;

// Where each kind lives in the scenario, and how a key path names it ("scene.spans[2]").
export const PLACES = {
  span: { path: ['scene', 'spans'], key: (i) => `scene.spans[${i}]` },
  pole: { path: ['scene', 'poles'], key: (i) => `scene.poles[${i}]` },
  tree: { path: ['scene', 'trees'], key: (i) => `scene.trees[${i}]` },
  fog: { path: ['weather', 'fog'], key: (i) => `weather.fog[${i}]` },
  mesh: { path: ['scene', 'meshes'], key: (i) => `scene.meshes[${i}]` },
};

function keyOf(base, path) {
  return path.reduce((key, part) => (typeof part === 'number' ? `${key}[${part}]` : `${key}.${part}`), base);
}

export class ObjectForms {
  // onEdit(path, value): a field changed; onDelete(kind, index); onPick(kind, id)
  constructor(list, form, { onEdit, onDelete, onPick }) {
    this.list = list;
    this.form = form;
    this.onEdit = onEdit;
    this.onDelete = onDelete;
    this.onPick = onPick;
    this.current = null;
    this.models = [];  // the model files of the scenario's folder (GET /api/models)
  }

  // Every object the scenario declares, by kind.
  showList(doc) {
    this.list.replaceChildren();
    for (const kind of ['span', 'pole', 'tree', 'mesh', 'fog']) {
      doc.list(PLACES[kind].path).forEach((item) => {
        const li = document.createElement('li');
        const button = document.createElement('button');
        button.type = 'button';
        button.textContent = `${kind} ${item?.id ?? '?'}`;
        button.dataset.object = `${kind}:${item?.id}`;
        button.addEventListener('click', () => this.onPick(kind, item?.id));
        li.append(button);
        this.list.append(li);
      });
    }
    if (doc.get(['scene', 'forest'])) {
      const li = document.createElement('li');
      const button = document.createElement('button');
      button.type = 'button';
      button.textContent = 'forest';
      button.dataset.object = 'forest:forest';
      button.addEventListener('click', () => this.onPick('forest', 'forest'));
      li.append(button);
      this.list.append(li);
    }
  }

  // The form of object `id` of `kind` (null: none).
  showForm(doc, kind, id) {
    this.form.replaceChildren();
    this.current = null;
    if (!kind) return;
    let base;
    let path;
    let index = -1;
    if (kind === 'forest') {
      base = 'scene.forest';
      path = ['scene', 'forest'];
    } else {
      index = doc.list(PLACES[kind].path).findIndex((item) => item?.id === id);
      if (index < 0) return;
      base = PLACES[kind].key(index);
      path = [...PLACES[kind].path, index];
    }
    this.current = { kind, id, index };
    const title = document.createElement('h3');
    title.textContent = `${kind} ${kind === 'forest' ? '' : id}`;
    this.form.append(title);
    for (const [label, sub, type, options] of FIELDS[kind]) {
      const row = document.createElement('label');
      row.className = 'field';
      row.dataset.key = keyOf(base, sub);
      const name = document.createElement('span');
      name.textContent = label;
      let input;
      if (type === 'select' || type === 'model') {
        input = document.createElement('select');
        const choices = type === 'model' ? this.models : options;
        for (const option of choices) input.append(new Option(option, option));
        const current = doc.get([...path, ...sub]);
        if (type === 'model' && current && !choices.includes(current)) input.append(new Option(current, current));
      } else {
        input = document.createElement('input');
        input.type = type;
        if (type === 'number') input.step = 'any';
      }
      const value = doc.get([...path, ...sub]);
      if (value !== undefined && value !== null) input.value = String(value);
      input.name = keyOf(base, sub);
      input.addEventListener('change', () => {
        const text = input.value.trim();
        const parsed = type === 'number' && text !== '' && Number.isFinite(Number(text)) ? Number(text) : text;
        this.onEdit([...path, ...sub], parsed);
      });
      const problem = document.createElement('span');
      problem.className = 'field-problem';
      row.append(name, input, problem);
      this.form.append(row);
    }
    const remove = document.createElement('button');
    remove.type = 'button';
    remove.textContent = `Delete ${kind}`;
    remove.addEventListener('click', () => this.onDelete(kind, index));
    this.form.append(remove);
  }

  // The loader's problem beside the field its key names; false when no field here names it.
  showProblem(problem) {
    let shown = false;
    for (const row of this.form.querySelectorAll('.field')) {
      const key = row.dataset.key;
      const here = problem && problem.key && (problem.key === key || key.startsWith(`${problem.key}[`));
      row.querySelector('.field-problem').textContent = here ? problem.problem : '';
      row.classList.toggle('bad', Boolean(here));
      shown = shown || Boolean(here);
    }
    return shown;
  }
}
