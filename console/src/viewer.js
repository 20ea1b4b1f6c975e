// The 3D view: orbit, zoom, reset, flat or smooth shading; a copy coloured by how far the mark
// moved each vertex along its normal, with the original beside it on request.
import * as THREE from '/console/vendor/three.module.js';
import { OrbitControls } from '/console/vendor/OrbitControls.js';

// Diverging blue (inward) - white - red (outward), t in [-1, 1].
function diverging(t, out) {
  const u = Math.max(-1, Math.min(1, t));
  if (u < 0) out.setRGB(1 + 0.87 * u, 1 + 0.6 * u, 1 + 0.33 * u);
  else out.setRGB(1 - 0.3 * u, 1 - 0.9 * u, 1 - 0.83 * u);
  return out;
}

// The displacement's scale: its 99th percentile of absolute values, so one outlier does not wash out the map.
export function displacementScale(values) {
  const sorted = Array.from(values, Math.abs).sort((a, b) => a - b);
  return sorted.length ? Math.max(sorted[Math.floor(0.99 * (sorted.length - 1))], 1e-12) : 1;
}

function geometryOf(mesh) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(mesh.positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(mesh.indices, 1));
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  return geometry;
}

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setSize(container.clientWidth, container.clientHeight);
    this.renderer.setClearColor(0xffffff);
    container.appendChild(this.renderer.domElement);
    this.renderer.domElement.setAttribute('aria-label', 'the mesh in 3D: drag to orbit, wheel to zoom');
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(35, container.clientWidth / container.clientHeight, 0.001, 1000);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x555566, 1.6));
    const light = new THREE.DirectionalLight(0xffffff, 1.4);
    light.position.set(1, 1, 2);
    this.camera.add(light);
    this.scene.add(this.camera);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());
    this.meshes = [];
    this.flat = false;
  }

  clear() {
    for (const m of this.meshes) { this.scene.remove(m); m.geometry.dispose(); m.material.dispose(); }
    this.meshes = [];
  }

  // layers: [{mesh, colour?, displacement?: bool, opacity?, name}]
  show(layers) {
    this.clear();
    for (const layer of layers) {
      const geometry = geometryOf(layer.mesh);
      const material = new THREE.MeshStandardMaterial({
        color: layer.colour ?? 0xb0b0b8, flatShading: this.flat, roughness: 0.7, metalness: 0.0,
        side: THREE.DoubleSide, transparent: (layer.opacity ?? 1) < 1, opacity: layer.opacity ?? 1,
      });
      if (layer.displacement && layer.mesh.displacement) {
        const scale = displacementScale(layer.mesh.displacement);
        const colours = new Float32Array(layer.mesh.displacement.length * 3);
        const c = new THREE.Color();
        layer.mesh.displacement.forEach((d, i) => diverging(d / scale, c).toArray(colours, 3 * i));
        geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
        material.vertexColors = true;
        material.color.set(0xffffff);
        layer.scale = scale;
      }
      const mesh = new THREE.Mesh(geometry, material);
      mesh.name = layer.name ?? '';
      this.meshes.push(mesh);
      this.scene.add(mesh);
    }
    this.reset();
  }

  setVisible(name, visible) {
    for (const m of this.meshes) if (m.name === name) m.visible = visible;
    this.render();
  }

  setFlat(flat) {
    this.flat = flat;
    for (const m of this.meshes) { m.material.flatShading = flat; m.material.needsUpdate = true; }
    this.render();
  }

  reset() {
    if (!this.meshes.length) return this.render();
    const sphere = this.meshes[0].geometry.boundingSphere;
    const distance = sphere.radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2));
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.position.copy(sphere.center).add(new THREE.Vector3(0, 0, distance * 1.05));
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(sphere.center);
    this.controls.update();
    this.render();
  }

  render() { this.renderer.render(this.scene, this.camera); }
}
