// corrugate web app: two tabs. "Analyse a design": the form, the analysis tables and the 3D view
// of the folded assembly. "Design from requirements": a spec form run as a design job
// (/api/jobs/design: progress as server-sent events, a cancel button), the certified design,
// its margins, the pattern, the 3D view, the files and an FE verification job.
// Plain ES module, no build step; three.js comes from /static/vendor (see the import map).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const TEXT_FIELDS = ['W', 'n', 'alpha', 'thickness', 'E', 'nu', 'density',
  'W2', 'n2', 'alpha2', 'thickness2', 'vertices'];
const CUSTOM = '__custom__';
// The palette's part colours (src/corrugate/fabrication/palette.py PARTS, the GLB's own materials):
// used only when a mesh comes without a colour. tests/fabrication/test_palette.py checks them.
const PART_COLOURS = { 'layer 1': 0x548cd9, 'layer 2': 0xf28c33, band: 0x9e9e9e };

const $ = (id) => document.getElementById(id);
const form = $('analyze-form');
const designForm = $('design-form');
let generation = 0;  // answers to an older submission are dropped

function fmt(x, digits = 4) {
  if (x === null || x === undefined) return '-';
  const a = Math.abs(x);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return x.toExponential(digits - 1);
  return String(Number(x.toPrecision(digits)));
}

// Fill ``td`` with ``text``, a line break allowed after each '.' and before each '[' of a spec
// path (<wbr>: the text itself, and what is copied from it, stays the path).
function breakable(td, text) {
  td.replaceChildren();
  for (const [i, part] of text.split(/(?<=\.)|(?=\[)/).entries()) {
    if (i) td.appendChild(document.createElement('wbr'));
    td.appendChild(document.createTextNode(part));
  }
  return td;
}

function cell(row, text, quantity) {
  const td = document.createElement('td');
  td.textContent = text;
  if (quantity) td.dataset.quantity = quantity;
  row.appendChild(td);
  return td;
}

// ---- units --------------------------------------------------------------------------------

// A plain number ("80", "-1.5e3"); anything else is left for the server to read.
const PLAIN_NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i;

// What the form posts for a value typed in a field that shows ``unit``: a plain number gets
// that unit ("80" in an EI field is "80 mN*m^2"), so that every quantity posted says its unit
// and a plain number is never read in another one; a value with a unit of its own is kept.
function withUnit(value, unit) {
  return unit && PLAIN_NUMBER.test(value) ? `${value} ${unit}` : value;
}

// ---- the form ----------------------------------------------------------------------------

async function loadMaterials() {
  const select = $('material');
  const select2 = $('material2');
  try {
    const response = await fetch('/api/materials');
    if (!response.ok) throw new Error(`HTTP ${response.status}`);
    const materials = await response.json();
    select.replaceChildren();
    const designSelect = $('d-material');
    designSelect.replaceChildren();
    for (const m of materials) {
      const label = `${m.id} (E ${fmt(m.E_MPa / 1000, 3)} GPa, t ${fmt(m.default_thickness_mm, 3)} mm)`;
      select.appendChild(new Option(label, m.id, false, m.id === 'dura-lar'));
      select2.appendChild(new Option(m.id, m.id));
      designSelect.appendChild(new Option(label, m.id, false, m.id === 'dura-lar'));
    }
    // an inline material (the spec's [material] E, nu, density, thickness, yield_strength)
    designSelect.appendChild(new Option('custom (E, nu, density below)', CUSTOM));
    await loadCasesLoaded;  // the design form's test menus too
    designForm.dataset.ready = 'true';
  } catch (err) {
    $('error-material').textContent = `could not load the material library: ${err.message}`;
    $('d-error-body').textContent = `could not load the material library: ${err.message}`;
  }
  select.appendChild(new Option('custom (E, nu, density below)', CUSTOM));
  form.dataset.ready = 'true';
}

function syncVisibility() {
  const custom = $('material').value === CUSTOM;
  for (const el of document.querySelectorAll('.inline-material')) el.hidden = !custom;
  $('vertices-field').hidden = $('layout').value !== 'polygon';
}

// Circular holes, "d@x,y; d@x,y" (mm, from the layout's centre) -> the API's hole tables,
// each length with its unit.
function holes(text) {
  return text.split(';').map((s) => s.trim()).filter((s) => s !== '').map((h) => {
    const [d, at] = h.split('@');
    const center = (at || '0,0').split(',').map((x) => withUnit(x.trim(), 'mm'));
    return { shape: 'circle', diameter: withUnit(d.trim(), 'mm'), center };
  });
}

function requestBody() {
  const body = {};
  for (const name of TEXT_FIELDS) {
    const el = $(name);
    if (el.closest('[hidden]')) continue;
    const value = el.value.trim();
    if (value !== '') body[name] = withUnit(value, el.dataset.unit);
  }
  const holeText = $('holes').value.trim();
  if (holeText !== '') body.holes = holes(holeText);
  const material = $('material').value;
  if (material !== CUSTOM) body.material = material;
  const material2 = $('material2').value;
  if (material2 !== '') body.material2 = material2;
  body.layout = $('layout').value;
  body.model = $('model').value;
  // "0 90" or "0 deg, 1.5 rad": directions, each posted with its unit
  const eta = $('eta').value.split(/[,;]+|\s+(?=[+-]?[\d.])/).map((s) => s.trim()).filter((s) => s !== '');
  if (eta.length) body.eta = eta.map((e) => withUnit(e, 'deg'));
  return body;
}

function clearErrors() {
  for (const el of document.querySelectorAll('.error')) el.textContent = '';
  for (const el of document.querySelectorAll('[aria-invalid]')) el.removeAttribute('aria-invalid');
}

// The name a user sees for a form control: its field's label, and its own aria-label when the
// label is shared (a min/max pair: "Side L (side max)").
function fieldName(input) {
  const sub = input.closest('label.sub');  // a requirement row's value: its own full name
  if (sub) return (input.getAttribute('aria-label') || '').trim() || sub.textContent.trim();
  const field = input.closest('.field');
  const label = field ? field.querySelector('label') : null;
  const text = label ? label.textContent.trim() : '';
  const own = (input.getAttribute('aria-label') || '').trim();
  if (label && label.htmlFor === input.id) return text || own || input.id;
  if (text && own) return `${text} (${own})`;
  return text || own || input.id;
}

// An error in plain words, the request's field (a TOML path on the design tab) second:
// "Side L (side min): you gave 70 mm, which is greater than max; allowed at most ... — constraints.side.min".
function plainError(e, input) {
  const message = String(e.message || '');
  if (!input || !e.field || e.field === 'body') return message;
  const name = fieldName(input);
  const prefix = `${e.field} = `;
  const tail = e.allowed ? `: allowed ${e.allowed}` : null;
  if (e.value != null && tail && message.startsWith(`${prefix}${e.value} `) && message.endsWith(tail)) {
    const reason = message.slice(prefix.length + String(e.value).length + 1, message.length - tail.length);
    const value = String(e.value).replace(/^'(.*)'$/, '$1');
    return `${name}: you gave ${value}, which ${reason}; allowed ${e.allowed} — ${e.field}`;
  }
  let rest = message;
  if (rest.startsWith(prefix)) rest = rest.slice(prefix.length);
  else if (rest.startsWith(`${e.field} `)) rest = rest.slice(e.field.length + 1);
  return `${name}: ${rest} — ${e.field}`;
}

function showErrors(payload, status) {
  const errors = (payload && payload.errors && payload.errors.length)
    ? payload.errors
    : [{ field: (payload && payload.field) || 'body', message: (payload && payload.detail) || `HTTP ${status}` }];
  for (const e of errors) {
    const base = String(e.field).split(/[[.]/)[0];  // holes[0].diameter -> holes
    let target = $(`error-${e.field}`) || $(`error-${base}`);
    const input = $(e.field) || $(base);
    if (target && target.closest('[hidden]')) target = null;
    if (input && target) input.setAttribute('aria-invalid', 'true');
    if (target && input && input.closest('details')) input.closest('details').open = true;
    (target || $('error-body')).textContent = target ? plainError(e, input) : e.message;
  }
}

async function postJSON(url, body) {
  const response = await fetch(url, {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify(body),
  });
  let payload = null;
  try { payload = await response.json(); } catch { payload = null; }
  return { ok: response.ok, status: response.status, payload };
}

// ---- the analysis ------------------------------------------------------------------------

function showAnalysis(r) {
  const size = r.L_mm !== null
    ? `L = ${fmt(r.L_mm)} mm`
    : `Lx = ${fmt(r.extent_x_mm)} mm, Ly = ${fmt(r.extent_y_mm)} mm`;
  const holeText = (r.layout.holes || []).map((h) => (h.shape === 'circle'
    ? `d ${fmt(h.diameter_mm)} mm at (${h.center_mm.map((c) => fmt(c)).join(', ')})`
    : `polygon at (${h.center_mm.map((c) => fmt(c)).join(', ')})`)).join('; ');
  $('summary').textContent = `layout ${r.layout.shape}: ${size}, folded thickness `
    + `t_d = ${fmt(r.thickness_mm)} mm, mass ${fmt(r.mass_g)} g; model ${r.model}`
    + (holeText ? `; holes ${holeText} mm` : '');
  $('model-source').textContent = r.model_source;

  const stiffness = $('stiffness').tBodies[0];
  stiffness.replaceChildren();
  for (const s of r.stiffness) {
    const row = stiffness.insertRow();
    row.dataset.eta = String(s.eta_deg);
    cell(row, fmt(s.eta_deg), 'eta_deg');
    cell(row, fmt(s.K_N_per_mm, 5), 'K_N_per_mm');
    cell(row, fmt(s.D_Nmm, 5), 'D_Nmm');
    cell(row, fmt(s.EI_Nmm2, 5), 'EI_Nmm2');
    cell(row, (s.EI_Nmm2 / 1000).toFixed(2), 'EI_mNm2');
  }

  const layers = $('layers').tBodies[0];
  layers.replaceChildren();
  for (const l of r.layers) {
    const row = layers.insertRow();
    cell(row, String(l.index));
    cell(row, l.material);
    cell(row, fmt(l.t_mm));
    cell(row, fmt(l.W_mm));
    cell(row, String(l.n));
    cell(row, fmt(l.alpha_deg));
    for (const k of ['Ecx', 'Ecy', 'Ebx', 'Eby']) cell(row, fmt(l.moduli_MPa[k]), k);
  }

  const m = r.mass_breakdown_g;
  const parts = Object.entries(m).filter(([k]) => k !== 'total_g')
    .map(([k, v]) => `${k.replace(/_g$/, '')} ${fmt(v)} g`).join(', ');
  $('mass').textContent = `${fmt(r.mass_g)} g (${parts})`;

  bulletList($('buckling'), r.buckling.map((b) => `along ${fmt(b.eta_deg)} deg: the end facets `
    + `buckle at ${fmt(b.low_N, 3)}-${fmt(b.high_N, 3)} N (plate theory; K holds below that; `
    + 'check with corrugate validate --buckling)'), 'not estimated for this layout');

  const warnings = $('warnings');
  warnings.replaceChildren();
  for (const w of r.warnings) {
    const li = document.createElement('li');
    setTextWithCode(li, `${w.code}: ${w.message}`);
    warnings.appendChild(li);
  }
  if (!r.warnings.length) {
    const li = document.createElement('li');
    li.textContent = 'none';
    li.className = 'muted';
    warnings.appendChild(li);
  }
  $('results').hidden = false;
}

// ---- the 3D view -------------------------------------------------------------------------

class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.appendChild(this.renderer.domElement);
    this.renderer.domElement.setAttribute('role', 'img');
    this.renderer.domElement.setAttribute(
      'aria-label', '3D view of the folded assembly: layer 1 blue, layer 2 orange, connector band grey');
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf4f6fa);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(1, -2, 3);
    this.scene.add(sun);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.1, 1e5);
    this.camera.up.set(0, 0, 1);  // the mesh is in mm with z up
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());
    this.model = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = this.container.clientWidth || 400;
    const h = this.container.clientHeight || 300;
    this.renderer.setSize(w, h, false);  // the canvas fills the box by CSS: no resize loop
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() { this.renderer.render(this.scene, this.camera); }

  setExploded(on) {
    this.exploded = on;
    (this.parts || []).forEach((o, i) => { o.position.z = on ? this.offsets[i] * this.gap : 0; });
    this.container.dataset.exploded = String(on);
    if (this.model) this.fit(true);  // the exploded model is taller: keep all of it in view
    this.render();
  }

  // Aim at the model's bounding box from a distance that keeps all of it in view; keepDirection
  // keeps the direction the user has turned the camera to (else the default oblique view).
  fit(keepDirection) {
    const box = new THREE.Box3().setFromObject(this.model);
    const center = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3()).length() || 1;
    const oblique = new THREE.Vector3(0.7, -1.0, 0.8);
    const away = keepDirection && this.fitted
      ? this.camera.position.clone().sub(this.controls.target)
      : oblique.clone();
    this.camera.near = size / 100;
    this.camera.far = size * 100;
    this.camera.position.copy(center).add(away.normalize().multiplyScalar(size * oblique.length()));
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
    this.fitted = true;
  }

  async show(url) {
    const gltf = await new GLTFLoader().loadAsync(url);
    if (this.model) {
      this.scene.remove(this.model);
      this.model.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    }
    // One mesh per part (layer 1, layer 2, band), each in its GLB material's colour.
    let triangles = 0;
    const parts = [];
    gltf.scene.traverse((o) => {
      if (o.isMesh) {
        const fallback = PART_COLOURS[o.name.replace(/_/g, ' ')] ?? PART_COLOURS['layer 1'];
        const color = o.material && o.material.color ? o.material.color.clone() : new THREE.Color(fallback);
        o.material = new THREE.MeshStandardMaterial({
          color, roughness: 0.65, metalness: 0.0, side: THREE.DoubleSide, flatShading: true,
        });
        parts.push(o);
        const g = o.geometry;
        triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
      }
    });
    this.model = gltf.scene;
    this.parts = parts;
    this.scene.add(this.model);
    const box = new THREE.Box3().setFromObject(this.model);
    // Exploded view: the layers move apart along z (below and above the band) by its height.
    const middle = box.getCenter(new THREE.Vector3()).z;
    this.gap = Math.max(box.max.z - box.min.z, 1);
    this.offsets = parts.map((o) => {
      if (/band/i.test(o.name)) return 0;
      const z = new THREE.Box3().setFromObject(o).getCenter(new THREE.Vector3()).z;
      if (Math.abs(z - middle) > 1e-9) return Math.sign(z - middle);
      return /2/.test(o.name) ? 1 : -1;
    });
    this.container.dataset.parts = parts.map((o) => o.name.replace(/_/g, ' ')).join(',');
    this.container.dataset.colors = parts.map((o) => `#${o.material.color.getHexString()}`).join(',');
    this.fitted = false;  // a new model: the default oblique view
    this.setExploded(this.exploded || false);
    return triangles;
  }
}

let viewer = null;

async function showMesh(body, mine) {
  const view = $('view3d');
  $('view').hidden = false;
  view.dataset.state = 'loading';
  const downloads = $('downloads');
  downloads.replaceChildren();
  const answer = await postJSON('/api/mesh', body);
  if (mine !== generation) return;
  if (!answer.ok) {
    view.dataset.state = 'error';
    showErrors(answer.payload, answer.status);
    return;
  }
  for (const f of answer.payload.files) {
    const li = document.createElement('li');
    const a = document.createElement('a');
    a.href = f.url;
    a.download = f.name;
    a.textContent = `${f.name} (${Math.ceil(f.bytes / 1024)} KiB)`;
    li.appendChild(a);
    downloads.appendChild(li);
  }
  const glb = answer.payload.files.find((f) => f.name.endsWith('.glb'));
  try {
    if (!viewer) viewer = new Viewer(view);
  } catch (err) {
    view.dataset.state = 'unavailable';
    view.textContent = `3D view unavailable here (WebGL): ${err.message}`;
    return;
  }
  const triangles = await viewer.show(glb.url);
  if (mine !== generation) return;
  view.dataset.triangles = String(triangles);
  view.dataset.state = 'ready';
}

// ---- submit ------------------------------------------------------------------------------

async function submit(event) {
  event.preventDefault();
  const mine = ++generation;
  clearErrors();
  $('cut-downloads').replaceChildren();  // the cut files of another design are not this one's
  $('cut-downloads').dataset.state = 'empty';
  const button = $('submit');
  button.disabled = true;
  $('status').textContent = 'analysing...';
  form.dataset.state = 'busy';
  try {
    const body = requestBody();
    const answer = await postJSON('/api/analyze', body);
    if (mine !== generation) return;
    if (!answer.ok) {
      showErrors(answer.payload, answer.status);
      $('results').hidden = true;  // never show the answer to other inputs as if it were this one's
      $('view').hidden = true;
      form.dataset.state = 'error';
      $('status').textContent = '';
      return;
    }
    showAnalysis(answer.payload);
    form.dataset.state = 'done';
    $('status').textContent = '';
    await showMesh(body, mine);
  } catch (err) {
    $('error-body').textContent = `request failed: ${err.message}`;
    form.dataset.state = 'error';
  } finally {
    if (mine === generation) {
      button.disabled = false;
      if (form.dataset.state === 'busy') form.dataset.state = 'done';
    }
  }
}

// ---- design from requirements -----------------------------------------------------------

let designGeneration = 0;
let designViewer = null;
// The kinds of file the server writes (GET /api/formats, read once): the download buttons follow
// their order; a file of no kind follows them, in the server's order.
let formats = [];

// A pattern's file names as a regular expression: '{sheet}' etc. stand for one or more
// characters other than '/', the rest is literal.
function patternRegExp(pattern) {
  const literal = pattern.split(/\{[a-z]+\}/).map((s) => s.replace(/[.*+?^${}()|[\]\\]/g, '\\$&'));
  return new RegExp(`^${literal.join('[^/]+')}$`);
}

const formatsLoaded = fetch('/api/formats')
  .then((response) => (response.ok ? response.json() : []))
  .then((list) => { formats = list.map((f) => ({ order: f.order, re: patternRegExp(f.pattern) })); })
  .catch(() => {});

function pathTokens(path) {
  const tokens = [];
  for (const part of path.split('.')) {
    const m = part.match(/^([^[\]]+)(?:\[(\d+)\])?$/);
    tokens.push(m[1]);
    if (m[2] !== undefined) tokens.push(Number(m[2]));
  }
  return tokens;
}

function setPath(obj, path, value) {
  const tokens = pathTokens(path);
  let o = obj;
  for (let i = 0; i < tokens.length - 1; i++) {
    const key = tokens[i];
    if (o[key] === undefined) o[key] = typeof tokens[i + 1] === 'number' ? [] : {};
    o = o[key];
  }
  o[tokens[tokens.length - 1]] = value;
}

function vertices(text) {
  return text.split(/\s+/).filter((s) => s !== '').map((p) => p.split(',').map((x) => {
    const v = Number(x);
    return Number.isFinite(v) ? v : x;  // the server names what cannot be read
  }));
}

function syncDesignVisibility() {
  const layout = $('d-layout').value;
  for (const el of designForm.querySelectorAll('[data-layouts]')) {
    el.hidden = !el.dataset.layouts.split(' ').includes(layout);
  }
  for (const el of designForm.querySelectorAll('[data-fold]')) {
    el.hidden = $('d-fold-style').value !== el.dataset.fold;
  }
  for (const el of designForm.querySelectorAll('[data-cutter]')) {
    el.hidden = $('d-cutter').value !== el.dataset.cutter;
  }
  $('d-objective-eta').hidden = $('d-objective').value.startsWith('minimize');
  const custom = $('d-material').value === CUSTOM;
  for (const el of designForm.querySelectorAll('.d-inline-material')) el.hidden = !custom;
  $('d-more-field').hidden = custom;  // the candidates are library ids
  renumberRequirements();
}

// ---- requirement rows: any number of EI, D, K, buckling and load-case bounds --------------

// The tests a row of each kind may name (docs/load_cases.md), made from the registry of load
// cases (GET /api/load-cases, read once): value '' is the spec's default (pure bending for EI and
// D, the support's own K between platens for K); a bending test for EI and D, an in-plane one
// for K (a test of one layout says which: 'wheel test (a circle)'), any but a stiffness-only one
// for a load case. null until read: the page's own first option stays.
let ROW_TESTS = null;
// The in-plane tests, which take no span (platens compress the whole panel).
const SPANLESS = new Set();

function rowTests(cases) {
  const asStiffness = (c) => [c.name, `${c.label} test${c.layouts.length === 1 ? ` (a ${c.layouts[0]})` : ''}`];
  const bending = [['', 'pure bending'], ...cases.filter((c) => c.kind === 'bending').map(asStiffness)];
  const own = cases.find((c) => c.own);
  const inplane = [['', own ? own.label : ''],
    ...cases.filter((c) => c.kind === 'inplane' && !c.own).map(asStiffness)];
  for (const c of cases) if (c.kind === 'inplane') SPANLESS.add(c.name);
  return {
    flexural_rigidity: bending,
    bending_stiffness: bending,
    inplane_stiffness: inplane,
    buckling_load: [],
    deflection: cases.filter((c) => c.deflection).map((c) => [c.name, c.label]),
  };
}

const loadCasesLoaded = fetch('/api/load-cases')
  .then((response) => (response.ok ? response.json() : []))
  .catch(() => [])
  .then((cases) => {
    ROW_TESTS = rowTests(cases);
    const names = ROW_TESTS.deflection.map(([, label]) => label);
    if (names.length) $('d-load-case-names').textContent = names.join(', ');
    renumberRequirements();
  });

// The test choices of a row for its kind (kept when the kind changes to one with the same list).
function syncRowTests(row) {
  if (ROW_TESTS === null) return;
  const kind = row.querySelector('.req-kind').value;
  const select = row.querySelector('.req-test');
  const tests = ROW_TESTS[kind] || [];
  if (select.dataset.kind !== kind) {
    const keep = select.value;
    select.replaceChildren(...tests.map(([value, label]) => new Option(label, value)));
    if (tests.some(([value]) => value === keep)) select.value = keep;
    select.dataset.kind = kind;
  }
  select.hidden = tests.length === 0;
}

// Give each row's inputs the spec path of their place: the k-th row of a kind is
// constraints.<kind>[k]; field errors from the server then land on the right row. A load-case
// row is constraints.deflection[k]: its value is the most deflection (`max`), with `load`,
// `test`, `span` and `bearing` (the width of its load lines; neither between platens).
function renumberRequirements() {
  const counts = {};
  const rows = [...$('d-req-rows').querySelectorAll('.req')];
  rows.forEach((row, i) => {
    syncRowTests(row);
    const kind = row.querySelector('.req-kind').value;
    const deflection = kind === 'deflection';
    const min = row.querySelector('.req-min');
    // a row switched to a quantity of another unit keeps no value of the old one (an EI of
    // "80 mN*m^2" is no deflection in mm); a load case's load and span go with it
    const was = row.dataset.kind;
    if (was !== undefined && was !== kind) {
      if (REQUIREMENT_UNITS[was] !== REQUIREMENT_UNITS[kind]) min.value = '';
      if (was === 'deflection') for (const c of ['.req-load', '.req-span', '.req-bearing']) row.querySelector(c).value = '';
    }
    row.dataset.kind = kind;
    row.querySelector('.req-min-text').textContent = deflection ? 'at most (mm)' : `at least (${REQUIREMENT_UNITS[kind]})`;
    const used = min.value.trim() !== '';
    const k = used ? (counts[kind] = (counts[kind] ?? -1) + 1) : null;
    const base = used ? `constraints.${kind}[${k}]` : null;
    const support = row.querySelector('.req-support');
    const test = row.querySelector('.req-test');
    const load = row.querySelector('.req-load');
    const span = row.querySelector('.req-span');
    const bearing = row.querySelector('.req-bearing');
    support.hidden = kind === 'buckling_load';  // a buckling bound has no support condition
    load.hidden = !deflection;
    span.hidden = !deflection || SPANLESS.has(test.value);  // platens compress the whole panel
    bearing.hidden = span.hidden;  // no load line between platens
    if (min.dataset.placeholder === undefined) min.dataset.placeholder = min.placeholder;
    min.placeholder = deflection ? 'at most, mm' : min.dataset.placeholder;
    const fields = [[min, deflection ? 'max' : 'min'], [row.querySelector('.req-eta'), 'eta'],
      [support, 'support'], [test, 'test'], [load, 'load'], [span, 'span'], [bearing, 'bearing']];
    for (const [el, key] of fields) {
      if (base && !el.hidden) el.dataset.path = `${base}.${key}`;
      else delete el.dataset.path;
    }
    const n = i + 1;
    row.querySelector('.req-kind').setAttribute('aria-label', `requirement ${n}: quantity`);
    min.setAttribute('aria-label', `requirement ${n}: ${deflection ? 'most deflection (mm)' : 'least value'}`);
    row.querySelector('.req-eta').setAttribute('aria-label', `requirement ${n}: direction eta (deg)`);
    support.setAttribute('aria-label', `requirement ${n}: support`);
    test.setAttribute('aria-label', `requirement ${n}: test`);
    load.setAttribute('aria-label', `requirement ${n}: load (N)`);
    span.setAttribute('aria-label', `requirement ${n}: span (mm; default: the panel's length along eta)`);
    bearing.setAttribute('aria-label', `requirement ${n}: bearing width of the load lines (mm; default 10 mm)`);
    row.querySelector('.req-remove').setAttribute('aria-label', `remove requirement ${n}`);
  });
}

// A new row (a copy of the first, emptied); ``values`` sets its fields: kind, min (the most
// deflection of a load case), eta, support, test, load, span, bearing.
function addRequirement(values = {}) {
  const rows = $('d-req-rows');
  const row = rows.querySelector('.req').cloneNode(true);
  for (const el of row.querySelectorAll('[id]')) el.removeAttribute('id');
  for (const el of row.querySelectorAll('[aria-invalid]')) el.removeAttribute('aria-invalid');
  row.querySelector('.error').textContent = '';
  rows.appendChild(row);
  setRequirement(row, { kind: 'flexural_rigidity', eta: '0 deg', ...values });
  return row;
}

function setRequirement(row, { kind, min = '', eta = '0 deg', support = '', test = '', load = '', span = '', bearing = '' }) {
  row.dataset.kind = kind;  // set, not switched: its values are the ones given
  row.querySelector('.req-kind').value = kind;
  syncRowTests(row);
  const select = row.querySelector('.req-test');
  if (test !== '' || [...select.options].some((o) => o.value === '')) select.value = test;
  row.querySelector('.req-min').value = String(min);
  row.querySelector('.req-eta').value = String(eta);
  row.querySelector('.req-support').value = support;
  row.querySelector('.req-load').value = String(load);
  row.querySelector('.req-span').value = String(span);
  row.querySelector('.req-bearing').value = String(bearing);
  renumberRequirements();
}

$('d-req-rows').addEventListener('click', (event) => {
  const button = event.target.closest('.req-remove');
  if (!button) return;
  const row = button.closest('.req');
  if ($('d-req-rows').querySelectorAll('.req').length > 1) row.remove();
  else for (const el of row.querySelectorAll('input')) el.value = '';
  renumberRequirements();
});
$('d-req-rows').addEventListener('input', renumberRequirements);
$('d-req-rows').addEventListener('change', renumberRequirements);
$('d-add-req').addEventListener('click', () => addRequirement().querySelector('.req-min').focus());

// The unit each requirement row's label shows; a plain number typed there is in that unit.
const REQUIREMENT_UNITS = {
  flexural_rigidity: 'mN*m^2', bending_stiffness: 'N*mm', inplane_stiffness: 'N/mm', buckling_load: 'N',
  deflection: 'mm',
};

// The unit a field shows (its data-unit; a requirement's value: its kind's unit).
function unitOf(el) {
  const row = el.closest('.req');
  if (row && el.classList.contains('req-min')) return REQUIREMENT_UNITS[row.querySelector('.req-kind').value];
  return el.dataset.unit;
}

// The spec (the keys of the TOML file) and the output options, from the visible fields.
function designBody() {
  renumberRequirements();
  const body = {};
  for (const el of designForm.querySelectorAll('[data-path]')) {
    if (el.closest('[hidden]') || el.hidden) continue;
    const value = el.value.trim();
    if (value === '') continue;
    if (el.dataset.requires && $(el.dataset.requires).value.trim() === '') continue;
    const kinds = { vertices, holes };
    setPath(body, el.dataset.path, kinds[el.dataset.kind] ? kinds[el.dataset.kind](value) : withUnit(value, unitOf(el)));
  }
  const [sense, what] = $('d-objective').value.split(':');
  body.objective = { ...(body.objective || {}), [sense]: what };
  if (sense === 'minimize') delete body.objective.eta;
  // an inline material is named by the spec's default name, as `[material] E = ...` without one
  if (body.material && body.material.name === CUSTOM) delete body.material.name;
  const more = $('d-more-materials').value.split(/[\s,;]+/).filter((x) => x !== '');
  if (more.length && body.material && !$('d-more-field').hidden) {
    const { name, ...rest } = body.material;
    const names = [name || $('d-material').value, ...more.filter((x) => x !== name)];
    body.materials = names.map((n) => ({ name: n, ...rest }));
    delete body.material;
  }
  if (body.cutter === 'laser') body.cutter = `laser:${$('d-laser-bed').value.trim().replace(/\s+/g, '')}`;
  return body;
}

window.designBodyForTests = designBody;  // the browser tests compare it with what was posted

// The form from a spec (the inverse of designBody), e.g. one shared in the page's URL. A text
// field the spec leaves out is emptied (the form's default is not the spec's), unless it is
// hidden once the form is filled (it sends nothing then): it keeps its default.
function fillDesign(spec) {
  const cleared = [...designForm.querySelectorAll('input[data-path]')].filter((el) => !el.closest('.req'));
  for (const el of cleared) el.value = '';
  const setField = (path, value) => {
    const el = designForm.querySelector(`[data-path="${path}"]`);
    if (el && value !== undefined && value !== null) el.value = Array.isArray(value) ? value.join(', ') : String(value);
  };
  const walk = (obj, prefix) => {
    for (const [key, value] of Object.entries(obj)) {
      const path = prefix ? `${prefix}.${key}` : key;
      if (value && typeof value === 'object' && !Array.isArray(value)) walk(value, path);
      else if (!['constraints.flexural_rigidity', 'constraints.bending_stiffness',
        'constraints.inplane_stiffness', 'constraints.buckling_load', 'constraints.deflection', 'layout.holes',
        'layout.vertices'].includes(path)) setField(path, value);
    }
  };
  // a spec that names no model is solved with refined (the form's own default is the case
  // study's paper)
  $('d-model').value = 'refined';
  $('d-joint').value = '';  // a spec that names no joint leaves the layers' edges free
  $('d-tolerances').value = '';  // a spec without [tolerances] is certified within the defaults
  for (const el of designForm.querySelectorAll('select[data-path^="fabrication."]')) el.value = '';  // the machine's
  // what a spec file cannot say is the CLI's default (a shared link's body names them all)
  $('d-cutter').value = 'cameo4-12x12';
  $('d-fold-style').value = 'machine';
  $('d-paper').value = 'mat';
  walk(spec, '');
  if (spec.layout && spec.layout.holes) {
    const mm = (x) => String(x).replace(/^(.*\S)\s*mm$/, '$1');  // the field's own unit
    $('d-holes').value = spec.layout.holes
      .map((h) => `${mm(h.diameter)}@${(h.center || [0, 0]).map(mm).join(',')}`).join('; ');
  }
  if (spec.layout && spec.layout.vertices) $('d-vertices').value = spec.layout.vertices.map((v) => v.join(',')).join(' ');
  const rows = $('d-req-rows');
  const keep = rows.querySelector('.req');
  for (const row of [...rows.querySelectorAll('.req')].slice(1)) row.remove();
  for (const el of keep.querySelectorAll('input')) el.value = '';
  let first = true;
  const c = spec.constraints || {};
  const fill = (values) => {
    if (first) setRequirement(keep, values);
    else addRequirement(values);
    first = false;
  };
  for (const kind of ['flexural_rigidity', 'bending_stiffness', 'inplane_stiffness', 'buckling_load']) {
    for (const b of c[kind] || []) {
      fill({ kind, min: b.min ?? '', eta: b.eta ?? '0 deg', support: b.support || '', test: b.test === 'pure' ? '' : (b.test || '') });
    }
  }
  for (const d of c.deflection || []) {
    fill({ kind: 'deflection', min: d.max ?? '', eta: d.eta ?? '0 deg', support: d.support || '',
      test: d.test || (ROW_TESTS.deflection[0] || [''])[0], load: d.load ?? '', span: d.span ?? '', bearing: d.bearing ?? '' });
  }
  const o = spec.objective || {};
  $('d-objective').value = o.maximize ? `maximize:${o.maximize}` : 'minimize:mass';
  if (spec.materials && spec.materials.length) {
    $('d-material').value = spec.materials[0].name;
    $('d-more-materials').value = spec.materials.slice(1).map((m) => m.name).join(', ');
    setField('material.thickness', spec.materials[0].thickness);
  }
  const m = spec.material || {};
  if (['E', 'nu', 'density'].some((k) => m[k] !== undefined)) $('d-material').value = CUSTOM;  // inline
  if (typeof spec.cutter === 'string' && spec.cutter.startsWith('laser:')) {
    $('d-cutter').value = 'laser';
    $('d-laser-bed').value = spec.cutter.slice(6);
  }
  syncDesignVisibility();
  for (const el of cleared) {
    if (el.value === '' && (el.hidden || el.closest('[hidden]'))) el.value = el.defaultValue;
  }
}

// The spec in the page's URL (#design?spec=...), so that a design can be shared as a link.
function specFromURL() {
  const m = location.hash.match(/^#design\?spec=(.*)$/);
  if (!m) return null;
  try { return JSON.parse(decodeURIComponent(m[1])); } catch { return null; }
}

// The field of a spec path (`constraints.side.min`), or of its closest parent with a field.
function designField(path) {
  const fields = [...designForm.querySelectorAll('[data-path]')].filter((el) => !el.closest('[hidden]'));
  let p = path;
  while (p) {
    const exact = fields.find((el) => el.dataset.path === p);
    if (exact) return exact;
    const below = fields.find((el) => el.dataset.path.startsWith(`${p}.`) || el.dataset.path.startsWith(`${p}[`));
    if (below) return below;
    const cut = Math.max(p.lastIndexOf('.'), p.lastIndexOf('['));
    p = cut > 0 ? p.slice(0, cut) : '';
  }
  return null;
}

function showDesignErrors(payload, status) {
  const errors = (payload && payload.errors && payload.errors.length)
    ? payload.errors
    : [{ field: (payload && payload.field) || 'body', message: (payload && payload.detail) || `HTTP ${status}` }];
  for (const e of errors) {
    const input = e.field ? designField(e.field) : null;
    const target = input ? input.closest('.field').querySelector('.error') : null;
    if (input) {
      input.setAttribute('aria-invalid', 'true');
      const details = input.closest('details');
      if (details) details.open = true;
    }
    (target || $('d-error-body')).textContent = target ? plainError(e, input) : e.message;
  }
}

function clearDesignErrors() {
  for (const el of designForm.querySelectorAll('.error')) el.textContent = '';
  for (const el of designForm.querySelectorAll('[aria-invalid]')) el.removeAttribute('aria-invalid');
}

// `text` into `el`, each span between backticks (a command or a spec key, quoted the command
// line's way, e.g. `corrugate docs fea`) a <code> element rather than printed backticks, as
// report.html shows them; a text with an unpaired backtick is shown as written.
function setTextWithCode(el, text) {
  const parts = String(text).split('`');
  if (parts.length % 2 === 0) {
    el.textContent = text;
    return;
  }
  el.replaceChildren();
  parts.forEach((part, k) => {
    if (k % 2) {
      const code = document.createElement('code');
      code.textContent = part;
      el.appendChild(code);
    } else if (part) {
      el.appendChild(document.createTextNode(part));
    }
  });
}

function bulletList(list, items, empty) {
  list.replaceChildren();
  for (const text of items) {
    const li = document.createElement('li');
    setTextWithCode(li, text);
    list.appendChild(li);
  }
  if (!items.length && empty) {
    const li = document.createElement('li');
    li.textContent = empty;
    li.className = 'muted';
    list.appendChild(li);
  }
}

function showDesign(d) {
  const found = d.design !== null;
  const extrapolated = (d.extrapolated || []).length > 0;
  let cert = extrapolated
    ? `extrapolated, not certified: outside the validated range (${d.extrapolated.join('; ')})`
    : (d.certified ? 'certified' : 'not certified');
  if (!extrapolated && d.tolerances && !d.tolerances.nominal) cert += ` ${d.tolerances.covers}`;
  $('d-verdict').textContent = `${d.name}: ${d.status} (${cert}), model ${d.model}`;
  $('d-verdict').dataset.status = d.status;
  $('d-found').hidden = !found;
  bulletList($('d-diagnosis'), d.diagnosis.map((x) => x.message));
  $('d-hint').textContent = d.hint ? `hint: ${d.hint}` : '';
  $('d-hint').hidden = !d.hint;
  if (found) {
    const g = d.design;
    const l1 = g.layers[0];
    const size = g.L_mm !== null
      ? `L = ${fmt(g.L_mm)} mm`
      : `Lx = ${fmt(g.extent_x_mm)} mm, Ly = ${fmt(g.extent_y_mm)} mm`;
    $('d-summary').textContent = `W = ${fmt(l1.W_mm, 6)} mm, n = ${l1.n}, \u03b1 = ${fmt(l1.alpha_deg, 6)} deg`
      + (g.layers.length > 1 && (g.layers[1].W_mm !== l1.W_mm || g.layers[1].n !== l1.n
        || g.layers[1].alpha_deg !== l1.alpha_deg)
        ? ` (layer 2: W = ${fmt(g.layers[1].W_mm, 6)} mm, n = ${g.layers[1].n}, \u03b1 = ${fmt(g.layers[1].alpha_deg, 6)} deg)`
        : ' (both layers)')
      + `; ${size}, folded thickness t_d = ${fmt(g.thickness_mm)} mm`;
    const layers = $('d-layers').tBodies[0];
    layers.replaceChildren();
    for (const l of g.layers) {
      const row = layers.insertRow();
      cell(row, String(l.index));
      cell(row, l.material);
      cell(row, fmt(l.t_mm));
      cell(row, fmt(l.W_mm, 6), 'W_mm');
      cell(row, String(l.n), 'n');
      cell(row, fmt(l.alpha_deg, 6), 'alpha_deg');
    }
    const m = d.performance.mass_breakdown_g;
    $('d-mass').textContent = `mass ${fmt(d.mass_g)} g: layer 1 ${fmt(m.layer1_g)} g, layer 2 `
      + `${fmt(m.layer2_g)} g, connectors ${fmt(m.connectors_g)} g`;
    const table = $('d-constraints').tBodies[0];
    table.replaceChildren();
    for (const c of d.constraints) {
      const row = table.insertRow();
      row.dataset.name = c.name;
      row.dataset.binding = c.binding === null ? '?' : (c.binding ? 'yes' : 'no');
      // a load case: the deflection (mm) under its load, and the test's P / delta
      const loadCase = c.load_N === undefined ? ''
        : ` (${c.test}, ${fmt(c.load_N)} N; P/\u03b4 = ${fmt(c.stiffness_N_per_mm, 4)} N/mm)`;
      // its capacity at the safety factor and first failure (docs/load_cases.md 10)
      const held = c.first_failure === undefined || c.load_capacity_N === undefined ? ''
        : `; holds ${fmt(c.load_capacity_N, 3)} N (first failure: ${c.first_failure})`;
      breakable(cell(row, ''), `${c.name}${loadCase}${held}`).className = 'text';
      cell(row, fmt(c.value, 5), 'value');
      cell(row, `${c.sense === 'min' ? '\u2265' : '\u2264'} ${fmt(c.bound, 5)}`, 'bound');
      cell(row, fmt(c.margin, 3), 'margin');
      cell(row, c.unit).className = 'text';
      cell(row, row.dataset.binding, 'binding');
    }
    showDesignStiffness(d);
    showRunnerUps(d);
  } else {
    $('d-summary').textContent = 'No design meets every requirement:';
  }
  bulletList($('d-warnings'), d.warnings.map((w) => `${w.code}: ${w.message}`)
    .concat((d.notes || []).map((w) => `note (${w.code}): ${w.message}`)), 'none');
  $('design-results').hidden = false;
}

// The answer's stiffness at each direction (the `stiffness` of corrugate design --json).
function showDesignStiffness(d) {
  const body = $('d-stiffness').tBodies[0];
  body.replaceChildren();
  for (const s of d.stiffness || []) {
    const row = body.insertRow();
    row.dataset.eta = String(s.eta_deg);
    cell(row, fmt(s.eta_deg), 'eta_deg');
    cell(row, fmt(s.K_N_per_mm, 5), 'K_N_per_mm');
    cell(row, fmt(s.D_Nmm, 5), 'D_Nmm');
    cell(row, fmt(s.EI_Nmm2 / 1000, 5), 'EI_mNm2');
  }
  const p = d.performance || {};
  const support = { free: 'free sides', frame: 'a rigid frame' }[p.support] || p.support || 'free sides';
  $('d-stiffness-note').textContent = `Model ${p.model || d.model}, support: ${support}; `
    + 'K in plane, D and EI in pure bending, at each direction \u03b7 from layer 1\'s creases.';
}

// The unit of an objective's value, from its quantity's key (mass, EI@0, Kframe@45, D@90...;
// the solver's internal units, as in the constraints table).
function objectiveUnit(key) {
  if (key === 'mass') return 'g';
  if (key.startsWith('EI')) return 'N mm\u00b2';
  if (key.startsWith('Pb')) return 'N';
  if (key.startsWith('D')) return 'N mm';
  if (key.startsWith('K')) return 'N/mm';
  return '';
}

// The runner-ups (best design for each n of layer 1), the answer's row marked; a layer-2 column
// only when some runner-up's layer 2 differs from its layer 1.
function showRunnerUps(d) {
  const runners = d.runner_ups || [];
  const key = d.objective.quantity;
  const unit = objectiveUnit(key);
  $('d-runner-objective').textContent = `${key}${unit ? ` (${unit})` : ''}`;
  const differs = (r) => r.layers.length > 1 && ['W_mm', 'n', 'alpha_deg', 'material', 't_mm']
    .some((k) => r.layers[1][k] !== r.layers[0][k]);
  const layer2 = runners.some(differs);
  for (const th of $('d-runner-ups').querySelectorAll('.layer2-col')) th.hidden = !layer2;
  const body = $('d-runner-ups').tBodies[0];
  body.replaceChildren();
  for (const r of runners) {
    const row = body.insertRow();
    const best = r.objective === d.objective.value;
    row.dataset.best = String(best);
    const l1 = r.layers[0];
    cell(row, String(r.n), 'n');
    cell(row, fmt(l1.W_mm, 6), 'W_mm');
    cell(row, fmt(l1.alpha_deg, 6), 'alpha_deg');
    if (layer2) {
      const l2 = r.layers[1];
      cell(row, differs(r) ? `W ${fmt(l2.W_mm, 6)}, n ${l2.n}, \u03b1 ${fmt(l2.alpha_deg, 6)}` : 'same', 'layer2')
        .className = 'text';
    }
    cell(row, fmt(r.objective, 6), 'objective');
    cell(row, `${r.certified ? 'yes' : 'no'}${best ? ' \u2605' : ''}`, 'certified');
  }
  if (!runners.length) {
    const row = body.insertRow();
    const n = (lastDesignSpec && lastDesignSpec.variables && lastDesignSpec.variables.n) || {};
    const single = n.min !== undefined && String(n.min) === String(n.max);
    const partial = (d.warnings || []).some((w) => w.code === 'explanation-partial');
    const td = cell(row, single ? 'none (a single n)'
      : partial ? 'none: the time budget ran out before the other n were searched'
        : 'none: no other n near the answer\'s meets every requirement');
    td.colSpan = layer2 ? 6 : 5;
    td.className = 'text muted';
  }
}

function rank(name) {
  const kind = formats.find((f) => f.re.test(name));
  return kind ? kind.order : Number.MAX_SAFE_INTEGER;
}

// The download links of a stored result (its files in a useful order, "Download all" first);
// returns the files in that order.
function fileLinks(downloads, result) {
  const files = [...result.files].sort((a, b) => rank(a.name) - rank(b.name));
  downloads.replaceChildren();
  if (files.length > 1) {
    const all = document.createElement('a');
    all.href = `/api/results/${result.id}/all.zip`;
    all.download = 'corrugate-design.zip';
    all.dataset.name = 'all.zip';
    all.textContent = `Download all (zip, ${files.length} files)`;
    downloads.appendChild(all);
  }
  for (const f of files) {
    const a = document.createElement('a');
    a.href = f.url;
    a.download = f.name;
    a.dataset.name = f.name;
    a.textContent = `${f.name} (${Math.ceil(f.bytes / 1024)} KiB)`;
    downloads.appendChild(a);
  }
  return files;
}

// The analyse tab's cut files: POST /api/pattern (what `corrugate pattern --out` writes).
async function makeCutFiles() {
  const button = $('make-cut-files');
  const box = $('cut-downloads');
  button.disabled = true;
  box.replaceChildren();
  $('error-cutter').textContent = '';
  box.dataset.state = 'busy';
  $('cut-status').textContent = 'writing the files...';
  try {
    const answer = await postJSON('/api/pattern', { ...requestBody(), cutter: $('cutter').value });
    if (!answer.ok) {
      showErrors(answer.payload, answer.status);
      box.dataset.state = 'error';
      return;
    }
    await formatsLoaded;
    fileLinks(box, answer.payload);
    box.dataset.state = 'ready';
  } catch (err) {
    $('error-cutter').textContent = `request failed: ${err.message}`;
    box.dataset.state = 'error';
  } finally {
    button.disabled = false;
    $('cut-status').textContent = '';
  }
}

function toggleExploded(button, getViewer) {
  const v = getViewer();
  const on = button.getAttribute('aria-pressed') !== 'true';
  button.setAttribute('aria-pressed', String(on));
  if (v) v.setExploded(on);
}

// The files of a design answer: already made (answer.result), else made now by POST
// answer.files_url (once per design on the server); null for an infeasible spec (no files).
async function designFiles(answer, mine) {
  if (answer.result || !answer.files_url) return answer.result;
  $('d-files').hidden = true;  // another design's files are not this one's
  $('d-status').textContent = 'making the files...';
  const made = await postJSON(answer.files_url, {});
  if (mine !== designGeneration) return null;
  $('d-status').textContent = '';
  if (!made.ok) {
    const detail = made.payload && made.payload.detail;
    if (made.status === 422 && made.payload) showDesignErrors(made.payload, 422);
    else $('d-error-body').textContent = `the files could not be made: ${detail || made.status}`;
    return null;
  }
  return made.payload;
}

async function showDesignFiles(result, mine) {
  const box = $('d-files');
  if (!result) {
    box.hidden = true;
    return;
  }
  await formatsLoaded;
  box.hidden = false;
  const files = fileLinks($('d-downloads'), result);
  const byName = Object.fromEntries(files.map((f) => [f.name, f]));
  // Every sheet of the written plan: the sheet-N.svg files themselves, in order.
  const sheets = files
    .filter((f) => /^sheet-\d+\.svg$/.test(f.name))
    .sort((a, b) => parseInt(a.name.slice(6), 10) - parseInt(b.name.slice(6), 10));
  const img = $('d-pattern');
  for (const extra of $('d-patterns').querySelectorAll('img:not(#d-pattern)')) extra.remove();
  img.hidden = sheets.length === 0;
  if (sheets.length) img.src = sheets[0].url;
  for (const [k, f] of sheets.slice(1).entries()) {
    const more = document.createElement('img');
    more.src = f.url;
    more.alt = `sheet ${k + 2} of the cut pattern`;
    more.dataset.name = f.name;
    $('d-patterns').appendChild(more);
  }
  img.dataset.name = sheets.length ? sheets[0].name : '';
  const report = byName['report.html'];
  $('d-report').hidden = !report;
  if (report) $('d-report-link').href = report.url;
  const view = $('d-view3d');
  const glb = byName['assembly.glb'];
  if (!glb) {
    view.dataset.state = 'empty';
    return;
  }
  view.dataset.state = 'loading';
  try {
    if (!designViewer) designViewer = new Viewer(view);
  } catch (err) {
    view.dataset.state = 'unavailable';
    view.textContent = `3D view unavailable here (WebGL): ${err.message}`;
    return;
  }
  const triangles = await designViewer.show(glb.url);
  if (mine !== designGeneration) return;
  view.dataset.triangles = String(triangles);
  view.dataset.state = 'ready';
}

// ---- jobs: a design or an FE verification running on the server, with progress ------------

// Follow a job (POST /api/jobs/... answered 202 with it) through its server-sent events: each
// progress event goes to ``onProgress``; resolves with the job's final state (done, failed or
// cancelled). A stream that breaks is resumed by the browser (Last-Event-ID); a job the server
// no longer knows ends as failed.
function followJob(job, onProgress) {
  return new Promise((resolve) => {
    const source = new EventSource(job.links.events);
    let settled = false;
    const settle = (state) => {
      if (settled) return;
      settled = true;
      source.close();
      resolve(state);
    };
    source.addEventListener('progress', (e) => { if (!settled) onProgress(JSON.parse(e.data)); });
    for (const kind of ['done', 'failed', 'cancelled']) {
      source.addEventListener(kind, (e) => settle(JSON.parse(e.data)));
    }
    source.onerror = async () => {
      if (settled || source.readyState !== EventSource.CLOSED) return;  // the browser retries
      try {
        const r = await fetch(job.links.status);
        const state = await r.json();
        if (r.ok && ['done', 'failed', 'cancelled'].includes(state.status)) { settle(state); return; }
        if (!r.ok) settle({ ...job, status: 'failed', error: { status: r.status, body: state } });
      } catch (err) {
        settle({ ...job, status: 'failed', error: { status: 0, body: { detail: `connection lost: ${err.message}` } } });
      }
    };
  });
}

async function cancelJob(id) {
  try { await fetch(`/api/jobs/${id}`, { method: 'DELETE' }); } catch { /* the stream ends it */ }
}

function seconds(x) { return `${fmt(x, 3)} s`; }

// One line of a design job's progress, and the share of its solver budget spent (0 to 1).
function designProgress(e, job) {
  const limit = `stopped at ${seconds(job.limits.time_limit_s)}`;
  if (e.stage === 'solving') {
    const objective = $('d-objective').value.split(':')[1];
    const unit = { mass: 'g', flexural_rigidity: 'N mm\u00b2', bending_stiffness: 'N mm',
      inplane_stiffness: 'N/mm' }[objective] || '';
    const best = e.best === null ? 'no design yet' : `best ${fmt(e.best, 5)}${unit ? ` ${unit}` : ''}`;
    const gap = e.gap === null ? '' : `, gap ${fmt(100 * e.gap, 3)} %`;
    const text = `branch and bound: ${e.iterations} iterations in ${e.runs} `
      + `${e.runs === 1 ? 'run' : 'runs'}${gap}, ${best}; ${seconds(e.cpu_s)} of the solver's `
      + `${seconds(e.budget_s)} CPU budget (${limit})${e.step ? `; now ${e.step}` : ''}`;
    return [text, e.budget_s ? Math.min(1, e.cpu_s / e.budget_s) : 0];
  }
  return [`reading the spec (solver budget ${seconds(job.limits.budget_s)} CPU, ${limit})`, 0];
}

function jobErrorText(state) {
  const err = state.error || {};
  const body = err.body || {};
  return body.detail || `the job failed (HTTP ${err.status})`;
}

let designJob = null;  // the id of the design job running, if any
let lastDesignSpec = null;  // the spec of the answer shown (its n range names empty runner-ups)

// Save the form as the spec file the CLI reads (the server writes the TOML: POST /api/spec/toml,
// the same checks as a design; a bad value is shown on its field and nothing is saved).
async function saveSpec() {
  clearDesignErrors();
  const body = designBody();
  $('d-status').textContent = '';
  try {
    const response = await fetch('/api/spec/toml', {
      method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
    });
    if (!response.ok) {
      showDesignErrors(await response.json().catch(() => ({})), response.status);
      return;
    }
    const text = await response.text();
    const link = document.createElement('a');
    link.href = URL.createObjectURL(new Blob([text], { type: 'text/plain' }));
    const name = String(body.name || 'design').replace(/[^A-Za-z0-9._-]+/g, '_');
    link.download = `${name}.toml`;
    document.body.appendChild(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.href), 10000);
    $('d-status').textContent = `saved ${link.download} (corrugate design ${link.download})`;
  } catch (err) {
    $('d-error-body').textContent = `request failed: ${err.message}`;
  }
}

// Load a spec file into the form (read by the server as the CLI reads it: POST /api/spec/parse;
// a bad file gets the CLI's one line naming the key, and the form is left as it was).
async function loadSpec(event) {
  const file = event.target.files && event.target.files[0];
  event.target.value = '';  // the same file may be loaded again
  if (!file) return;
  clearDesignErrors();
  try {
    const answer = await postJSON('/api/spec/parse', { toml: await file.text(), name: file.name });
    if (!answer.ok) {
      const p = answer.payload || {};
      $('d-error-body').textContent = `${file.name}: ${p.detail || `HTTP ${answer.status}`}`;
      return;
    }
    await loadCasesLoaded;  // the rows' test menus first
    fillDesign(answer.payload);
    // the keys of the file the form has no field for (saving the form would leave them out)
    const paths = (obj, prefix = '') => Object.entries(obj).flatMap(([k, v]) => (
      v && typeof v === 'object' && !Array.isArray(v) ? paths(v, `${prefix}${k}.`) : [`${prefix}${k}`]));
    const kept = new Set(paths(designBody()));
    const lost = paths(answer.payload).filter((p) => !kept.has(p));
    $('d-status').textContent = `loaded ${file.name}${lost.length ? `; not in the form (left out): ${lost.join(', ')}` : ''}`;
  } catch (err) {
    $('d-error-body').textContent = `request failed: ${err.message}`;
  }
}

async function submitDesign(event) {
  event.preventDefault();
  const mine = ++designGeneration;
  clearDesignErrors();
  if (designJob) cancelJob(designJob);  // a new spec replaces the one being designed
  designJob = null;
  const button = $('d-submit');
  const cancel = $('d-cancel');
  const bar = $('d-progress');
  button.disabled = true;
  $('d-status').textContent = 'designing...';
  designForm.dataset.state = 'busy';
  delete designForm.dataset.job;
  $('d-progress-text').textContent = '';  // never the last run's progress as this run's
  try {
    const body = designBody();
    lastDesignSpec = body;
    history.replaceState(null, '', `#design?spec=${encodeURIComponent(JSON.stringify(body))}`);
    const answer = await postJSON('/api/jobs/design', body);
    if (mine !== designGeneration) return;
    if (!answer.ok) {
      showDesignErrors(answer.payload, answer.status);
      $('design-results').hidden = true;  // never show another spec's answer as this one's
      designForm.dataset.state = 'error';
      $('d-status').textContent = '';
      return;
    }
    const job = answer.payload;
    designJob = job.id;
    designForm.dataset.job = job.id;
    cancel.hidden = false;
    $('d-progress-box').hidden = false;
    bar.value = 0;
    $('d-progress-text').textContent = designProgress({ stage: 'queued' }, job)[0];
    const state = await followJob(job, (e) => {
      if (mine !== designGeneration) return;
      const [text, share] = designProgress(e, job);
      $('d-progress-text').textContent = text;
      bar.value = share;
      designForm.dataset.events = String(e.seq);
    });
    if (mine !== designGeneration) return;
    designJob = null;
    cancel.hidden = true;
    $('d-progress-box').hidden = true;
    if (state.status === 'cancelled') {
      $('d-status').textContent = 'cancelled';
      $('design-results').hidden = true;  // an earlier answer is not this spec's
      designForm.dataset.state = 'cancelled';
      return;
    }
    if (state.status !== 'done') {
      const err = state.error || {};
      if (err.status === 422 && err.body) showDesignErrors(err.body, 422);
      else $('d-error-body').textContent = jobErrorText(state);
      $('design-results').hidden = true;
      designForm.dataset.state = 'error';
      $('d-status').textContent = '';
      return;
    }
    showDesign(state.result.design);
    $('d-status').textContent = '';
    resetVerify(null);
    // the answer arrived: take the reader (and a screen reader's focus) to it
    const heading = $('d-result-heading');
    heading.focus({ preventScroll: true });
    heading.scrollIntoView({ block: 'start' });
    // answers first: the files are made on demand (once per design) and then shown
    const result = await designFiles(state.result, mine);
    if (mine !== designGeneration) return;
    resetVerify(result);
    await showDesignFiles(result, mine);
    if (mine === designGeneration) designForm.dataset.state = 'done';
  } catch (err) {
    $('d-error-body').textContent = `request failed: ${err.message}`;
    designForm.dataset.state = 'error';
  } finally {
    if (mine === designGeneration) {
      button.disabled = false;
      cancel.hidden = true;
      $('d-progress-box').hidden = true;
      if (designForm.dataset.state === 'busy') designForm.dataset.state = 'done';
    }
  }
}

$('d-cancel').addEventListener('click', () => {
  if (!designJob) return;
  $('d-status').textContent = 'cancelling...';
  cancelJob(designJob);
});

// ---- FE verification of a design (POST /api/jobs/verify: corrugate verify) ----------------

let verifyResult = null;  // the stored result of the design shown
let verifyJob = null;
let fea = null;  // GET /api/fea: whether CalculiX is installed on the server

const feaLoaded = fetch('/api/fea').then((r) => r.json()).then((info) => { fea = info; })
  .catch((err) => { fea = { available: false, message: `cannot ask the server: ${err.message}` }; });

async function resetVerify(result) {
  if (verifyJob) cancelJob(verifyJob);
  verifyJob = null;
  verifyResult = result ? result.id : null;
  $('d-verify-log').replaceChildren();
  $('d-verify-table').hidden = true;
  $('d-verify-cancel').hidden = true;
  const box = $('d-verify');
  delete box.dataset.state;
  await feaLoaded;
  box.disabled = !fea.available || !verifyResult;
  $('d-verify-status').textContent = fea.available ? '' : fea.message;
  box.dataset.state = fea.available ? 'ready' : 'unavailable';
}

function showVerification(v) {
  const body = $('d-verify-table').tBodies[0];
  body.replaceChildren();
  for (const c of v.constraints) {
    const row = body.insertRow();
    cell(row, `${c.name} [${c.quantity}]`, 'name').className = 'text';
    const bound = c.bound === null ? '-' : `${c.sense === 'max' ? '\u2264' : '\u2265'} ${fmt(c.bound, 5)} ${c.unit}`;
    cell(row, bound.trim(), 'bound');
    cell(row, fmt(c.model, 5), 'model');
    let series = Object.values(c.fe_series).map((x) => fmt(x, 5)).join(' / ') || '-';
    const at = Object.keys(c.fe_series);
    if (at.length && at.join(',') !== v.meshes.join(',')) series += ` (at ${at.join(' / ')})`;  // extended
    cell(row, series, 'fe_series');
    const notes = [c.estimate ? `(${c.estimate})` : '', c.note || ''].filter(Boolean).join('; ');
    cell(row, `${fmt(c.fe, 5)}${notes ? ` ${notes}` : ''}`, 'fe').className = 'text';
    const verdict = c.verdict || (c.holds ? 'holds' : 'fails');
    const holds = cell(row, { holds: 'yes', fails: 'NO' }[verdict] || verdict, 'holds');
    holds.dataset.holds = String(c.holds);
    holds.dataset.verdict = verdict;
  }
  $('d-verify-caption').textContent = `${v.design}: mesh series ${v.meshes.join(' / ')} elements `
    + `per facet, ${v.runs} CalculiX ${v.runs === 1 ? 'run' : 'runs'}`;
  $('d-verify-table').hidden = false;
  $('d-verify-status').textContent = v.statement || (v.constraints.length
    ? ({
      holds: 'every constraint holds in FE',
      fails: 'not every constraint holds in FE',
      'not converged': 'no constraint fails, but not every FE series converged: not shown to hold',
      'not checked': 'every constraint with an FE twin holds; the others are not checked by FE',
    }[v.verdict || (v.holds ? 'holds' : 'fails')])
    : 'no behavioural constraint: nothing for the FE to check');
}

async function verifyDesign() {
  const button = $('d-verify');
  const status = $('d-verify-status');
  const log = $('d-verify-log');
  if (!verifyResult) return;
  button.disabled = true;
  button.dataset.state = 'busy';
  log.replaceChildren();
  $('d-verify-table').hidden = true;
  status.textContent = 'starting the FE runs...';
  const mine = verifyResult;
  try {
    const answer = await postJSON('/api/jobs/verify', { result: verifyResult, mesh: $('d-verify-mesh').value });
    if (!answer.ok) {
      status.textContent = (answer.payload && answer.payload.detail) || `HTTP ${answer.status}`;
      button.dataset.state = 'error';
      return;
    }
    const job = answer.payload;
    verifyJob = job.id;
    button.dataset.job = job.id;
    $('d-verify-cancel').hidden = false;
    status.textContent = `running (stopped at ${seconds(job.limits.time_limit_s)})...`;
    const state = await followJob(job, (e) => {
      if (e.stage !== 'fe' || mine !== verifyResult) return;
      const li = document.createElement('li');
      li.textContent = e.line;
      log.appendChild(li);
    });
    if (mine !== verifyResult) return;
    verifyJob = null;
    if (state.status === 'done') {
      showVerification(state.result);
      button.dataset.state = 'done';
    } else {
      status.textContent = state.status === 'cancelled' ? 'cancelled' : jobErrorText(state);
      button.dataset.state = state.status === 'cancelled' ? 'cancelled' : 'error';
    }
  } catch (err) {
    status.textContent = `request failed: ${err.message}`;
    button.dataset.state = 'error';
  } finally {
    if (mine === verifyResult) {
      button.disabled = false;
      $('d-verify-cancel').hidden = true;
    }
  }
}

$('d-verify').addEventListener('click', verifyDesign);
$('d-verify-cancel').addEventListener('click', () => { if (verifyJob) cancelJob(verifyJob); });

// ---- tabs --------------------------------------------------------------------------------

// The WAI-ARIA tabs pattern (automatic activation): the chosen tab is the tab list's one tab
// stop (roving tabindex); Left/Right move to the previous/next tab (wrapping round), Home/End
// to the first/last, and the tab moved to is chosen.
function selectTab(name, focus = false) {
  for (const tab of document.querySelectorAll('[role="tab"]')) {
    const on = tab.id === `tab-${name}`;
    tab.setAttribute('aria-selected', String(on));
    tab.tabIndex = on ? 0 : -1;
    $(tab.getAttribute('aria-controls')).hidden = !on;
    if (on && focus) tab.focus();
  }
  if (!location.hash.startsWith(`#${name}`)) history.replaceState(null, '', `#${name}`);
}

const TABS = [...document.querySelectorAll('[role="tab"]')];
for (const tab of TABS) {
  tab.addEventListener('click', () => selectTab(tab.id.slice(4)));
  tab.addEventListener('keydown', (event) => {
    const i = TABS.indexOf(tab);
    const to = { ArrowRight: i + 1, ArrowLeft: i - 1, Home: 0, End: TABS.length - 1 }[event.key];
    if (to === undefined) return;
    event.preventDefault();
    selectTab(TABS[(to + TABS.length) % TABS.length].id.slice(4), true);
  });
}
if (location.hash.startsWith('#design')) selectTab('design');

form.addEventListener('submit', submit);
$('material').addEventListener('change', syncVisibility);
$('d-material').addEventListener('change', syncDesignVisibility);
$('layout').addEventListener('change', syncVisibility);
designForm.addEventListener('submit', submitDesign);
$('d-save').addEventListener('click', saveSpec);
$('d-load').addEventListener('change', loadSpec);
$('make-cut-files').addEventListener('click', makeCutFiles);
$('explode').addEventListener('click', (event) => toggleExploded(event.currentTarget, () => viewer));
$('d-explode').addEventListener('click', (event) => toggleExploded(event.currentTarget, () => designViewer));
$('d-layout').addEventListener('change', syncDesignVisibility);
$('d-fold-style').addEventListener('change', syncDesignVisibility);
$('d-cutter').addEventListener('change', syncDesignVisibility);
$('d-objective').addEventListener('change', syncDesignVisibility);
syncVisibility();
syncDesignVisibility();
Promise.all([loadMaterials(), loadCasesLoaded]).then(() => {
  syncVisibility();
  const shared = specFromURL();
  if (shared) fillDesign(shared);
});
