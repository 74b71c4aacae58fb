// corrugate web app: the form, the analysis tables and the 3D view of the folded assembly.
// Plain ES module, no build step; three.js comes from /static/vendor (see the import map).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const TEXT_FIELDS = ['W', 'n', 'alpha', 'thickness', 'E', 'nu', 'density',
  'W2', 'n2', 'alpha2', 'thickness2', 'vertices'];
const CUSTOM = '__custom__';

const $ = (id) => document.getElementById(id);
const form = $('analyze-form');
let generation = 0;  // answers to an older submission are dropped

function fmt(x, digits = 4) {
  if (x === null || x === undefined) return '-';
  const a = Math.abs(x);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return x.toExponential(digits - 1);
  return String(Number(x.toPrecision(digits)));
}

function cell(row, text, quantity) {
  const td = document.createElement('td');
  td.textContent = text;
  if (quantity) td.dataset.quantity = quantity;
  row.appendChild(td);
  return td;
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
    for (const m of materials) {
      const label = `${m.id} (E ${fmt(m.E_MPa / 1000, 3)} GPa, t ${fmt(m.default_thickness_mm, 3)} mm)`;
      select.appendChild(new Option(label, m.id, false, m.id === 'dura-lar'));
      select2.appendChild(new Option(m.id, m.id));
    }
  } catch (err) {
    $('error-material').textContent = `could not load the material library: ${err.message}`;
  }
  select.appendChild(new Option('custom (E, nu, density below)', CUSTOM));
  form.dataset.ready = 'true';
}

function syncVisibility() {
  const custom = $('material').value === CUSTOM;
  for (const el of document.querySelectorAll('.inline-material')) el.hidden = !custom;
  $('vertices-field').hidden = $('layout').value !== 'polygon';
}

function requestBody() {
  const body = {};
  for (const name of TEXT_FIELDS) {
    const el = $(name);
    if (el.closest('[hidden]')) continue;
    const value = el.value.trim();
    if (value !== '') body[name] = value;
  }
  const material = $('material').value;
  if (material !== CUSTOM) body.material = material;
  const material2 = $('material2').value;
  if (material2 !== '') body.material2 = material2;
  body.layout = $('layout').value;
  body.model = $('model').value;
  const eta = $('eta').value.split(/[\s,;]+/).filter((s) => s !== '');
  if (eta.length) body.eta = eta;
  return body;
}

function clearErrors() {
  for (const el of document.querySelectorAll('.error')) el.textContent = '';
  for (const el of document.querySelectorAll('[aria-invalid]')) el.removeAttribute('aria-invalid');
}

function showErrors(payload, status) {
  const errors = (payload && payload.errors && payload.errors.length)
    ? payload.errors
    : [{ field: (payload && payload.field) || 'body', message: (payload && payload.detail) || `HTTP ${status}` }];
  for (const e of errors) {
    let target = $(`error-${e.field}`);
    const input = $(e.field);
    if (target && target.closest('[hidden]')) target = null;
    if (input && target) input.setAttribute('aria-invalid', 'true');
    if (target && input && input.closest('details')) input.closest('details').open = true;
    (target || $('error-body')).textContent = e.message;
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
  $('summary').textContent = `layout ${r.layout.shape}: ${size}, folded thickness `
    + `t_d = ${fmt(r.thickness_mm)} mm, mass ${fmt(r.mass_g)} g; model ${r.model}`;
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

  const warnings = $('warnings');
  warnings.replaceChildren();
  for (const w of r.warnings) {
    const li = document.createElement('li');
    li.textContent = `${w.code}: ${w.message}`;
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

  async show(url) {
    const gltf = await new GLTFLoader().loadAsync(url);
    if (this.model) {
      this.scene.remove(this.model);
      this.model.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    }
    const material = new THREE.MeshStandardMaterial({
      color: 0x9cc0e8, roughness: 0.65, metalness: 0.0, side: THREE.DoubleSide, flatShading: true,
    });
    let triangles = 0;
    gltf.scene.traverse((o) => {
      if (o.isMesh) {
        o.material = material;
        const g = o.geometry;
        triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
      }
    });
    this.model = gltf.scene;
    this.scene.add(this.model);
    const box = new THREE.Box3().setFromObject(this.model);
    const center = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3()).length() || 1;
    this.camera.near = size / 100;
    this.camera.far = size * 100;
    this.camera.position.copy(center).add(new THREE.Vector3(0.7, -1.0, 0.8).multiplyScalar(size));
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
    this.render();
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

form.addEventListener('submit', submit);
$('material').addEventListener('change', syncVisibility);
$('layout').addEventListener('change', syncVisibility);
syncVisibility();
loadMaterials().then(syncVisibility);
