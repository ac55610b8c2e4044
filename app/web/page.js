// The share page of `rouge export web` (docs/FORMATS.md, "rouge export web"): the look's .glb
// drawn by three.js with a before/after slider (bare skin | look) and the look's products.
// Everything it needs is in the page: this script with three.js bundled into it
// (tests/web/bundle.mjs writes page.bundle.js), and in <script> elements the page data
// (#rouge-data, JSON), the .glb (#rouge-glb) and the bare skin's base colour (#rouge-bare),
// both base64. It loads nothing, so it opens from disk (file://) with no network.
//
// The view is Rouge's camera with one white directional light from the camera of irradiance π
// (`rouge render --lights front`): a white Lambertian facing it shows 1.0. Drag to turn the head.
// `#embed` shows the canvas alone at the window's size with the look (`#embed-bare`: the bare
// skin), for screenshots beside Rouge's frames. The body gets data-ready="1" after the first frame.
import {
  DirectionalLight,
  Color,
  PerspectiveCamera,
  Scene,
  SRGBColorSpace,
  Texture,
  Vector3,
  WebGLRenderer,
} from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const data = JSON.parse(document.getElementById('rouge-data').textContent);

function bytesOf(id) {
  const text = document.getElementById(id).textContent.trim();
  const raw = atob(text);
  const out = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; i++) out[i] = raw.charCodeAt(i);
  return out;
}

const embed = location.hash.startsWith('#embed');
if (embed) document.body.classList.add('embed');
const canvas = document.getElementById('view');
const renderer = new WebGLRenderer({ canvas, antialias: !embed, preserveDrawingBuffer: true });
renderer.outputColorSpace = SRGBColorSpace;
renderer.setClearColor(new Color(data.background[0], data.background[1], data.background[2]), 1);

const scene = new Scene();
const cam = data.camera;
const camera = new PerspectiveCamera(cam.fov_y_deg, 1, cam.near_m, cam.far_m);
camera.position.fromArray(cam.position_m);
const target = new Vector3().fromArray(cam.target_m);
camera.lookAt(target);
// The light follows the camera: a headlight of irradiance π (three.js: radiance = albedo/π × E).
const light = new DirectionalLight(0xffffff, Math.PI);
scene.add(light);
scene.add(light.target);
const controls = new OrbitControls(camera, canvas);
controls.target.copy(target);
controls.enableDamping = false;
controls.enabled = !embed;

let split = embed ? (location.hash === '#embed-bare' ? 1 : 0) : 0.5;
let skin = null;
let lookMaterial = null;
let bareMaterial = null;

function resize() {
  const w = canvas.clientWidth;
  const h = canvas.clientHeight;
  renderer.setPixelRatio(embed ? 1 : window.devicePixelRatio);
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}

function draw() {
  if (!skin) return;
  light.position.copy(camera.position);
  light.target.position.copy(controls.target);
  const size = renderer.getDrawingBufferSize(new Vector3());
  const [w, h] = [size.x / renderer.getPixelRatio(), size.y / renderer.getPixelRatio()];
  const x = Math.round(split * w);
  renderer.setScissorTest(true);
  for (const [x0, x1, material] of [[0, x, bareMaterial], [x, w, lookMaterial]]) {
    if (x1 <= x0) continue;
    skin.material = material;
    renderer.setScissor(x0, 0, x1 - x0, h);
    renderer.render(scene, camera);
  }
  renderer.setScissorTest(false);
  const handle = document.getElementById('handle');
  if (handle) handle.style.left = `${split * 100}%`;
}

function products() {
  const list = document.getElementById('products');
  for (const p of data.products) {
    const row = document.createElement('li');
    const swatch = document.createElement('span');
    swatch.className = 'swatch';
    swatch.style.background = p.swatch;
    const name = document.createElement('strong');
    name.textContent = p.product;
    const what = document.createElement('span');
    what.textContent = ` ${p.kind}${p.finish ? `, ${p.finish}` : ''} (layer "${p.layer}")`;
    row.append(swatch, name, what);
    list.append(row);
  }
  if (data.products.length === 0) list.textContent = 'No product: the bare skin.';
}

function fail(message) {
  console.error(message);
  document.getElementById('status').textContent = message;
}

document.title = `${data.look} - Rouge`;
document.getElementById('title').textContent = data.look;
products();
const slider = document.getElementById('split');
slider.value = String(split * 100);
slider.addEventListener('input', () => {
  split = Number(slider.value) / 100;
  draw();
});
controls.addEventListener('change', draw);
window.addEventListener('resize', () => {
  resize();
  draw();
});
resize();

const glb = bytesOf('rouge-glb');
new GLTFLoader().parse(
  glb.buffer,
  '',
  (gltf) => {
    scene.add(gltf.scene);
    skin = gltf.scene.getObjectByName('skin');
    if (skin && !skin.isMesh) skin = skin.children.find((c) => c.isMesh) ?? null;
    if (!skin) return fail('the .glb has no mesh named "skin"');
    lookMaterial = skin.material;
    // The bare skin: its own base colour, the skin's one lobe (no layer's roughness or F0).
    bareMaterial = lookMaterial.clone();
    const image = new Image();
    image.onload = () => {
      const map = new Texture(image);
      map.flipY = false;
      map.colorSpace = SRGBColorSpace;
      map.needsUpdate = true;
      bareMaterial.map = map;
      bareMaterial.roughnessMap = null;
      bareMaterial.metalnessMap = null;
      bareMaterial.roughness = data.bare.roughness;
      bareMaterial.metalness = 0;
      if ('specularIntensityMap' in bareMaterial) {
        bareMaterial.specularIntensityMap = null;
        bareMaterial.specularIntensity = 1;
        bareMaterial.specularColor.setRGB(1, 1, 1);
      }
      bareMaterial.needsUpdate = true;
      draw();
      document.body.dataset.ready = '1';
    };
    image.onerror = () => fail('the bare skin texture did not decode');
    image.src = `data:image/png;base64,${document.getElementById('rouge-bare').textContent.trim()}`;
  },
  (error) => fail(`the .glb did not load: ${error.message ?? error}`),
);
