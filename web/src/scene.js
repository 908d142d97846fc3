// The 3-D view: sparse and dense points, the occupancy grid on its floor, the trajectory and
// ground truth, keyframes as camera frusta, loop closures and the current camera. The map's frame is the camera's (x right, y down,
// z forward), so "up" on screen is -y.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const kFrustumDepth = 0.08;  // m, drawn size of a keyframe's frustum
const kFrustumHalfWidth = 0.05;
const kFrustumHalfHeight = 0.0375;

const kColors = {
  sparse: 0x202020,
  trajectory: 0x1f6fd1,
  groundTruth: 0x2aa84a,
  keyframe: 0x8a3fc7,
  loop: 0xe02020,
  current: 0xff8800,
};

// RGBA of the grid's cells (GridCell: 1 free, 2 occupied); unknown cells stay transparent.
const kGridFree = [200, 225, 205, 140];
const kGridOccupied = [70, 70, 70, 230];

// Rotates (x, y, z) by the unit quaternion (qx, qy, qz, qw).
function rotate(q, x, y, z) {
  const [qx, qy, qz, qw] = q;
  // v + 2w (q x v) + 2 q x (q x v)
  const cx = qy * z - qz * y;
  const cy = qz * x - qx * z;
  const cz = qx * y - qy * x;
  const ccx = qy * cz - qz * cy;
  const ccy = qz * cx - qx * cz;
  const ccz = qx * cy - qy * cx;
  return [x + 2 * (qw * cx + ccx), y + 2 * (qw * cy + ccy), z + 2 * (qw * cz + ccz)];
}

// Line segments of a camera frustum at `pose` ([t, x, y, z, qx, qy, qz, qw]), appended to `out`.
function appendFrustum(pose, scale, out) {
  const origin = [pose[1], pose[2], pose[3]];
  const q = [pose[4], pose[5], pose[6], pose[7]];
  const corner = (sx, sy) => {
    const r = rotate(q, sx * kFrustumHalfWidth * scale, sy * kFrustumHalfHeight * scale,
                     kFrustumDepth * scale);
    return [origin[0] + r[0], origin[1] + r[1], origin[2] + r[2]];
  };
  const corners = [corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)];
  for (let i = 0; i < 4; ++i) {
    out.push(...origin, ...corners[i]);
    out.push(...corners[i], ...corners[(i + 1) % 4]);
  }
}

function lineGeometry(values) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(values, 3));
  return geometry;
}

export class MapScene {
  constructor(canvas) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(0xf4f4f0);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(60, 1, 0.01, 500);
    this.camera.up.set(0, -1, 0);
    this.controls = new OrbitControls(this.camera, canvas);
    this.objects = {};
    this.denseChunks = [];
    this.fitted = false;
    this.scale = 1;
    // Drawn only after a change (new data, the mouse, a resize): an idle page costs no CPU,
    // which matters when the browser shares the machine with the run.
    this.dirty = true;
    this.controls.addEventListener('change', () => { this.dirty = true; });
    this.resize();
    window.addEventListener('resize', () => this.resize());
    const loop = () => {
      this.controls.update();
      if (this.dirty) {
        this.dirty = false;
        this.renderer.render(this.scene, this.camera);
      }
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  resize() {
    const canvas = this.renderer.domElement;
    const width = canvas.clientWidth || window.innerWidth;
    const height = canvas.clientHeight || window.innerHeight;
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / Math.max(1, height);
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  replace(name, object) {
    if (this.objects[name]) {
      this.scene.remove(this.objects[name]);
      this.objects[name].geometry?.dispose();
    }
    this.objects[name] = object;
    if (object) this.scene.add(object);
    this.dirty = true;
  }

  setSparse(positions) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    const material = new THREE.PointsMaterial({ color: kColors.sparse, size: 3, sizeAttenuation: false });
    this.replace('sparse', new THREE.Points(geometry, material));
  }

  // A dense chunk: float32 xyz and uint8 rgb (or null: grey).
  addDenseChunk(positions, colors) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    let material;
    if (colors && colors.length === positions.length) {
      geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3, true));
      material = new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, vertexColors: true });
    } else {
      material = new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, color: 0x909090 });
    }
    const points = new THREE.Points(geometry, material);
    this.denseChunks.push(points);
    this.scene.add(points);
    this.dirty = true;
  }

  clearDense() {
    for (const chunk of this.denseChunks) {
      this.scene.remove(chunk);
      chunk.geometry.dispose();
    }
    this.denseChunks = [];
    this.dirty = true;
  }

  // The occupancy grid (data.js: decodeGrid) as a textured plane in its floor frame, placed by
  // T_world_grid; null removes it.
  setGrid(grid) {
    if (!grid) {
      this.replace('grid', null);
      return;
    }
    const { width, height, resolution } = grid;
    const pixels = new Uint8Array(width * height * 4);
    for (let i = 0; i < width * height; ++i) {
      if (grid.cells[i] === 1) pixels.set(kGridFree, 4 * i);
      if (grid.cells[i] === 2) pixels.set(kGridOccupied, 4 * i);
    }
    // Texture row 0 is the plane's lowest y, as the grid's row 0 is.
    const texture = new THREE.DataTexture(pixels, width, height, THREE.RGBAFormat);
    texture.magFilter = THREE.NearestFilter;
    texture.minFilter = THREE.NearestFilter;
    texture.needsUpdate = true;
    const sizeX = width * resolution;
    const sizeY = height * resolution;
    const geometry = new THREE.PlaneGeometry(sizeX, sizeY);
    geometry.translate(grid.origin[0] + sizeX / 2, grid.origin[1] + sizeY / 2, 0);
    const material = new THREE.MeshBasicMaterial({
      map: texture, transparent: true, side: THREE.DoubleSide, depthWrite: false,
    });
    const mesh = new THREE.Mesh(geometry, material);
    mesh.matrixAutoUpdate = false;
    mesh.matrix.set(...grid.T_world_grid);  // row-major, as Matrix4.set takes it
    this.replace('grid', mesh);
  }

  setTrajectory(poses) {
    const values = [];
    for (const p of poses) values.push(p[1], p[2], p[3]);
    const material = new THREE.LineBasicMaterial({ color: kColors.trajectory });
    this.replace('trajectory', values.length >= 6 ? new THREE.Line(lineGeometry(values), material) : null);
    this.setCurrent(poses.length ? poses[poses.length - 1] : null);
  }

  setGroundTruth(positions) {
    const values = [];
    for (const p of positions) values.push(p[1], p[2], p[3]);
    const material = new THREE.LineDashedMaterial({ color: kColors.groundTruth, dashSize: 0.02, gapSize: 0.01 });
    const line = values.length >= 6 ? new THREE.Line(lineGeometry(values), material) : null;
    line?.computeLineDistances();
    this.replace('groundTruth', line);
  }

  setKeyframes(poses) {
    const values = [];
    for (const p of poses) appendFrustum(p, this.scale, values);
    const material = new THREE.LineBasicMaterial({ color: kColors.keyframe });
    this.replace('keyframes', values.length ? new THREE.LineSegments(lineGeometry(values), material) : null);
  }

  setCurrent(pose) {
    if (!pose) {
      this.replace('current', null);
      return;
    }
    const values = [];
    appendFrustum(pose, this.scale * 1.6, values);
    const material = new THREE.LineBasicMaterial({ color: kColors.current });
    this.replace('current', new THREE.LineSegments(lineGeometry(values), material));
  }

  // Loop closures: a ring of short red spokes around each closing pose.
  setLoops(positions) {
    const values = [];
    const r = 0.06 * this.scale;
    for (const [x, y, z] of positions) {
      values.push(x - r, y, z, x + r, y, z, x, y - r, z, x, y + r, z, x, y, z - r, x, y, z + r);
    }
    const material = new THREE.LineBasicMaterial({ color: kColors.loop });
    this.replace('loops', values.length ? new THREE.LineSegments(lineGeometry(values), material) : null);
  }

  // Frames the view on the trajectory (or the points) once, when there is something to see.
  fit(poses, positions) {
    if (this.fitted) return;
    const box = new THREE.Box3();
    for (const p of poses) box.expandByPoint(new THREE.Vector3(p[1], p[2], p[3]));
    if (box.isEmpty() && positions && positions.length >= 3) {
      for (let i = 0; i < positions.length; i += 3) {
        box.expandByPoint(new THREE.Vector3(positions[i], positions[i + 1], positions[i + 2]));
      }
    }
    if (box.isEmpty()) return;
    const size = Math.max(box.getSize(new THREE.Vector3()).length(), 0.5);
    this.scale = Math.min(Math.max(size / 4, 0.5), 5);
    const centre = box.getCenter(new THREE.Vector3());
    this.controls.target.copy(centre);
    this.camera.position.set(centre.x - 0.4 * size, centre.y - 1.2 * size, centre.z - 1.6 * size);
    this.camera.near = size / 500;
    this.camera.far = size * 200;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
    this.fitted = poses.length > 1;
  }
}
