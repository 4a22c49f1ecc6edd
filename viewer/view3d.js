// The 3D view shared by Reeve's pages (the replay of `reeve run --html`
// and the live page of `reeve view`): bodies drawn by their shapes, a
// spoke on each wheel, cables as the polylines Reeve sends (coloured by
// their highest span tension), an orbit camera starting at the scene's.
// `head` is the scene's fixed part (tools/src/viewer_files.h, sceneHead).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

/// Blue (0 N) through yellow to red (`max` N and above).
export function tensionColor(t, max) {
  const x = max > 0 ? Math.min(1, Math.max(0, t / max)) : 0;
  const low = new THREE.Color(0x3060c0), mid = new THREE.Color(0xd0a020), high = new THREE.Color(0xd02020);
  return x < 0.5 ? low.lerp(mid, 2 * x) : mid.lerp(high, 2 * x - 1);
}

function shapeGeometry(shape) {
  switch (shape.type) {
    case 'box': {
      const [x, y, z] = shape.half_extents;
      return new THREE.BoxGeometry(2 * x, 2 * y, 2 * z);
    }
    case 'cylinder': {  // Reeve's cylinders lie along their local z
      const g = new THREE.CylinderGeometry(shape.radius, shape.radius, 2 * shape.half_length, 48);
      g.rotateX(Math.PI / 2);
      return g;
    }
    case 'sphere':
      return new THREE.SphereGeometry(shape.radius, 32, 16);
    case 'hull': {
      const positions = [];
      for (const face of shape.faces)  // a fan over each convex face
        for (let k = 1; k + 1 < face.length; ++k)
          for (const i of [face[0], face[k], face[k + 1]]) positions.push(...shape.vertices[i]);
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
      g.computeVertexNormals();
      return g;
    }
  }
  return new THREE.BufferGeometry();
}

// A spoke from the centre out along local x shows a wheel turning.
function spoke(shape) {
  if (shape.type !== 'cylinder' && shape.type !== 'sphere') return null;
  const reach = shape.radius, depth = shape.type === 'cylinder' ? shape.half_length : 0;
  const g = new THREE.BoxGeometry(reach, 0.08 * reach, 0.02 * reach + 1e-4);
  g.translate(reach / 2, 0, depth + 0.01 * reach);
  return new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: 0xc04020 }));
}

/// The view of `head` inside `container`. `poses` (7 numbers a body: x, y,
/// z, qx, qy, qz, qw) and `paths` (per cable, its polylines as flat x, y,
/// z, ...) of the first frame frame the camera when the scene has none.
/// `onError(text)` hears why there is no WebGL (the rest still works).
/// `renderer`: one kept from a view before (dispose(true)), whose WebGL
/// context is reused; by default a new one.
export class View3D {
  constructor(container, head, poses, paths, onError, renderer = null) {
    this.container = container;
    this.head = head;
    this.renderer = renderer;
    if (!renderer) {
      try {
        this.renderer = new THREE.WebGLRenderer({ antialias: true });
        this.renderer.setPixelRatio(window.devicePixelRatio);
        container.appendChild(this.renderer.domElement);
      } catch (e) {
        onError(`No 3D view: ${e.message}`);
      }
    }
    const scene = this.scene = new THREE.Scene();
    scene.background = new THREE.Color(0xf4f4f2);
    scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(3, 5, 4);
    scene.add(sun);
    this.bodyMeshes = head.bodies.map((body, i) => {
      const material = new THREE.MeshStandardMaterial({
        color: body.dynamic ? 0x8fa8c8 : 0x9a9a9a, roughness: 0.7, metalness: 0.1,
      });
      const mesh = new THREE.Mesh(shapeGeometry(body.shape), material);
      const marker = spoke(body.shape);
      if (marker) mesh.add(marker);
      for (const outline of body.outlines || []) {  // sections its shape does not show
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.Float32BufferAttribute(outline, 3));
        mesh.add(new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0x404850 })));
      }
      mesh.userData = { kind: 'body', index: i, name: body.name };
      scene.add(mesh);
      return mesh;
    });
    this.cableGroups = head.cables.map((cable, c) => {
      const group = new THREE.Group();
      group.userData = { kind: 'cable', index: c };
      scene.add(group);
      return group;
    });
    // The camera: the scene's, or one framing the first frame.
    const camera = this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    const box = new THREE.Box3();
    for (let k = 0; k + 2 < poses.length; k += 7) box.expandByPoint(new THREE.Vector3(poses[k], poses[k + 1], poses[k + 2]));
    for (const cable of paths) for (const piece of cable)
      for (let k = 0; k + 2 < piece.length; k += 3) box.expandByPoint(new THREE.Vector3(piece[k], piece[k + 1], piece[k + 2]));
    if (head.camera) {
      camera.fov = head.camera.fov_y_deg;
      camera.position.set(...head.camera.eye);
      camera.up.set(...head.camera.up);
    } else {
      const centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3()).length() || 1;
      camera.position.copy(centre).add(new THREE.Vector3(0, 0, 1.6 * size));
    }
    const target = head.camera ? new THREE.Vector3(...head.camera.target) : box.getCenter(new THREE.Vector3());
    camera.lookAt(target);
    this.controls = this.renderer ? new OrbitControls(camera, this.renderer.domElement) : null;
    if (this.controls) this.controls.target.copy(target);
    // The camera moved since the last render() (a page that draws only
    // when something changed reads it).
    this.moved = true;
    if (this.controls) this.controls.addEventListener('change', () => { this.moved = true; });
    this.ray = new THREE.Raycaster();
    this.ray.params.Line.threshold = 0.03;
  }

  /// Frees the GPU's copies (a scene reloaded); the renderer too, unless
  /// `keepRenderer`. Returns the renderer kept, if any.
  dispose(keepRenderer = false) {
    this.scene.traverse((o) => { if (o.geometry) o.geometry.dispose(); if (o.material) o.material.dispose(); });
    if (this.controls) this.controls.dispose();
    if (!this.renderer || keepRenderer) return this.renderer;
    this.renderer.dispose();
    this.renderer.domElement.remove();
    return null;
  }

  resize(width, height) {
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    if (this.renderer) this.renderer.setSize(width, height);
  }

  /// Moves body i to poses[7 i .. 7 i + 7).
  setPoses(poses) {
    this.bodyMeshes.forEach((mesh, i) => {
      mesh.position.set(poses[7 * i], poses[7 * i + 1], poses[7 * i + 2]);
      mesh.quaternion.set(poses[7 * i + 3], poses[7 * i + 4], poses[7 * i + 5], poses[7 * i + 6]);
    });
  }

  /// Redraws cable c as paths[c]'s polylines in the colour of the highest
  /// of tensions[c] on the scale 0 .. maxTension N; with `spans` (per
  /// cable, each joint's start and end point: 6 numbers, NaN while
  /// disabled), the polylines grey and every pulling span over them in the
  /// colour of its own tension.
  setCables(paths, tensions, maxTension, spans = null) {
    // The lines are kept from frame to frame and their buffers written in
    // place while their sizes hold (hilbert3: 511 spans, 60 frames a second).
    this.cableGroups.forEach((group, c) => {
      let high = 0;
      for (const t of tensions[c]) high = Math.max(high, t);
      const color = spans ? new THREE.Color(0x606060) : tensionColor(high, maxTension);
      const lines = group.userData.lines || (group.userData.lines = []);
      paths[c].forEach((piece, i) => {
        let line = lines[i];
        if (!line || line.geometry.attributes.position.array.length !== piece.length) {
          if (line) { group.remove(line); line.geometry.dispose(); line.material.dispose(); }
          const g = new THREE.BufferGeometry();
          g.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(piece.length), 3));
          line = lines[i] = new THREE.Line(g, new THREE.LineBasicMaterial());
          line.userData = { kind: 'cable', index: c, span: -1 };
          group.add(line);
        }
        line.geometry.attributes.position.array.set(piece);
        line.geometry.attributes.position.needsUpdate = true;
        line.geometry.computeBoundingSphere();
        line.material.color.copy(color);
      });
      for (const extra of lines.splice(paths[c].length)) {
        group.remove(extra);
        extra.geometry.dispose();
        extra.material.dispose();
      }
      if (!spans) return;
      // Every pulling span, one segment each in the colour of its tension.
      const joints = tensions[c].length;
      let overlay = group.userData.spans;
      if (!overlay || overlay.userData.spanOf.length !== joints) {
        if (overlay) { group.remove(overlay); overlay.geometry.dispose(); overlay.material.dispose(); }
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(6 * joints), 3));
        g.setAttribute('color', new THREE.Float32BufferAttribute(new Float32Array(6 * joints), 3));
        overlay = group.userData.spans = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: true }));
        overlay.userData = { kind: 'cable', index: c, spanOf: new Int32Array(joints) };
        overlay.renderOrder = 1;  // after the grey lines it lies on, which it covers
        group.add(overlay);
      }
      const position = overlay.geometry.attributes.position, colour = overlay.geometry.attributes.color;
      let n = 0;
      for (let j = 0; j < joints; ++j) {
        const t = tensions[c][j], ends = spans[c].subarray(6 * j, 6 * j + 6);
        if (!(t > 0) || Number.isNaN(ends[0])) continue;
        position.array.set(ends, 6 * n);
        const rgb = tensionColor(t, maxTension);
        for (const k of [0, 3]) { colour.array[6 * n + k] = rgb.r; colour.array[6 * n + k + 1] = rgb.g; colour.array[6 * n + k + 2] = rgb.b; }
        overlay.userData.spanOf[n++] = j;
      }
      overlay.geometry.setDrawRange(0, 2 * n);
      overlay.userData.count = n;
      position.needsUpdate = colour.needsUpdate = true;
      overlay.geometry.computeBoundingSphere();
    });
  }

  /// Link markers in the paper's colours (as the PNGs draw them): rolling
  /// red, attachment green, pinhole blue, a hybrid by what it is now (3:
  /// rolling, red; 4: tied, green); kinds[m] at positions[3 m ..].
  setMarkers(kinds, positions) {
    const colours = [0xd02020, 0x20a040, 0x2050d0, 0xd02020, 0x20a040];
    if (!this.markers || this.markers.instanceMatrix.count < kinds.length) {  // room for them all
      if (this.markers) { this.scene.remove(this.markers); this.markers.geometry.dispose(); this.markers.material.dispose(); }
      const radius = 0.004 * this.camera.position.distanceTo(this.controls ? this.controls.target : new THREE.Vector3());
      // Over everything, as the PNGs draw them: a tie point inside its body shows.
      this.markers = new THREE.InstancedMesh(new THREE.SphereGeometry(radius, 10, 6),
                                             new THREE.MeshBasicMaterial({ depthTest: false }), Math.max(16, 2 * kinds.length));
      this.markers.frustumCulled = false;
      this.markers.renderOrder = 1;
      this.scene.add(this.markers);
    }
    const place = new THREE.Matrix4(), colour = new THREE.Color();
    for (let m = 0; m < kinds.length; ++m) {
      this.markers.setMatrixAt(m, place.makeTranslation(positions[3 * m], positions[3 * m + 1], positions[3 * m + 2]));
      this.markers.setColorAt(m, colour.setHex(colours[kinds[m]] ?? 0x000000));
    }
    this.markers.count = kinds.length;
    this.markers.instanceMatrix.needsUpdate = true;
    if (this.markers.instanceColor) this.markers.instanceColor.needsUpdate = true;
  }

  render() {
    if (this.controls) this.controls.update();
    if (this.renderer) this.renderer.render(this.scene, this.camera);
    this.moved = false;
  }

  /// The ray through a mouse event's pixel.
  rayAt(event) {
    const r = this.renderer.domElement.getBoundingClientRect();
    this.ray.setFromCamera(new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1,
                                             -((event.clientY - r.top) / r.height) * 2 + 1), this.camera);
    return this.ray;
  }

  /// The cable ({cable: index, span: its joint's index, -1 off the spans
  /// setCables colours}) or body ({body: index, point: the point
  /// hit, world}) under a mouse event, cables first (bodies first with
  /// `bodiesFirst`); null for neither.
  pick(event, bodiesFirst = false) {
    if (!this.renderer) return null;
    const ray = this.rayAt(event);
    const cableHit = () => {
      const hit = ray.intersectObjects(this.cableGroups, true).find((h) =>
        h.object.userData.kind === 'cable' && (!h.object.userData.spanOf || h.index / 2 < h.object.userData.count));
      if (!hit) return null;
      const data = hit.object.userData;
      return { cable: data.index, span: data.spanOf ? data.spanOf[Math.floor(hit.index / 2)] : -1 };
    };
    const bodyHit = () => {
      const hit = ray.intersectObjects(this.bodyMeshes, false)[0];
      return hit ? { body: hit.object.userData.index, point: hit.point } : null;
    };
    return bodiesFirst ? bodyHit() || cableHit() : cableHit() || bodyHit();
  }

  /// What a screenshot's test needs to find the bodies (it projects them
  /// itself): each dynamic body's centre (m, world), the camera's view
  /// matrix (column-major) and vertical field of view (deg).
  projection() {
    const centres = {};
    this.head.bodies.forEach((body, i) => { if (body.dynamic) centres[body.name] = this.bodyMeshes[i].position.toArray(); });
    return { centres, view_matrix: this.camera.matrixWorldInverse.toArray(), fov_y_deg: this.camera.fov };
  }
}
