// bodyview's page script (a classic script, so that it runs from file://). It links the inline
// three.js modules through blob URLs, loads the inline GLB, and sets each link node's transform
// itself from the link's offset (X_PL, double precision, from the page data) and its joint
// position, so that what is drawn is what window.bodyview.linkMatrix reports.
(function () {
  'use strict';
  let resolveReady, rejectReady;
  const api = { ready: new Promise((resolve, reject) => { resolveReady = resolve; rejectReady = reject; }) };
  window.bodyview = api;

  function bytes(base64) {
    const text = atob(base64.replace(/\s+/g, ''));
    const out = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) out[i] = text.charCodeAt(i);
    return out;
  }

  // three.js's modules import each other by relative path or as 'three': each is turned into a
  // blob URL, after the specifiers it imports are replaced by the blob URLs made before it.
  async function importThree() {
    const specifiers = {
      'three': 'three.module.js', './three.core.js': 'three.core.js',
      '../utils/BufferGeometryUtils.js': 'BufferGeometryUtils.js', '../utils/SkeletonUtils.js': 'SkeletonUtils.js',
    };
    const urls = {};
    const decoder = new TextDecoder();
    for (const element of document.querySelectorAll('script.bv-module')) {
      const source = decoder.decode(bytes(element.textContent)).replace(
        /(\bfrom\s*)(['"])([^'"\n]+)\2/g,
        (match, from, quote, name) => (urls[specifiers[name]] ? from + quote + urls[specifiers[name]] + quote : match));
      urls[element.dataset.name] = URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
    }
    const THREE = await import(urls['three.module.js']);
    const { GLTFLoader } = await import(urls['GLTFLoader.js']);
    const { OrbitControls } = await import(urls['OrbitControls.js']);
    return { THREE, GLTFLoader, OrbitControls };
  }

  function el(tag, attributes, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attributes || {})) {
      if (k === 'class') e.className = v;
      else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v);
    }
    for (const c of children) e.append(c);
    return e;
  }

  const fmt = (v, digits = 4) => (v === null || v === undefined ? '∞' : Number(v).toPrecision(digits).replace(/\.?0+(e|$)/, '$1'));
  const vec = (v) => '[' + v.map((x) => fmt(x)).join(', ') + ']';

  async function main() {
    const timings = (api.timings = { start: performance.now() });
    const data = JSON.parse(document.getElementById('bv-data').textContent);
    const glb = bytes(document.getElementById('bv-glb').textContent);
    const { THREE, GLTFLoader, OrbitControls } = await importThree();
    timings.imported = performance.now();
    document.title = data.model + ' — bodyview';
    document.getElementById('title').textContent = data.model + ' (' + data.links.length + ' links, ' + fmt(data.total_mass) + ' kg)';

    // glTF node names as written (three.js renames nodes it loads). The first parse leaves the
    // collision nodes out (three.js then builds none of their meshes: half the work on a large
    // model); the whole GLB is parsed again when collision geometry is first switched on.
    const jsonLength = new DataView(glb.buffer, glb.byteOffset).getUint32(12, true);
    const gltfJson = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
    // Names are the model's data (a link may be called 'arm/collision'): a node's role is read
    // from the extras body2gltf writes, and a geometry group's link from its parent node.
    const geometryOf = (k) => (gltfJson.nodes[k].extras || {}).geometry;
    const isCollision = (k) => geometryOf(k) === 'collision';
    const parentNode = [];
    gltfJson.nodes.forEach((n, p) => (n.children || []).forEach((k) => { parentNode[k] = p; }));
    const nodeLink = new Map();  // GLB node index -> link index
    const visualJson = { ...gltfJson, nodes: gltfJson.nodes.map((n) => (n.children ? { ...n, children: n.children.filter((k) => !isCollision(k)) } : n)) };
    const parse = (json) => new Promise((resolve, reject) => new GLTFLoader().parse(withJson(json), '', resolve, reject));
    function withJson(json) {
      const text = new TextEncoder().encode(JSON.stringify(json));
      const padded = (text.length + 3) & ~3;
      const bin = glb.subarray(20 + jsonLength);  // the BIN chunk with its header
      const out = new Uint8Array(20 + padded + bin.length);
      const view = new DataView(out.buffer);
      view.setUint32(0, 0x46546c67, true);  // glTF
      view.setUint32(4, 2, true);
      view.setUint32(8, out.length, true);
      view.setUint32(12, padded, true);
      view.setUint32(16, 0x4e4f534a, true);  // JSON
      out.set(text, 20);
      out.fill(0x20, 20 + text.length, 20 + padded);
      out.set(bin, 20 + padded);
      return out.buffer;
    }
    const gltf = await parse(visualJson);

    timings.parsed = performance.now();
    const links = data.links;
    const linkIndex = new Map(), jointIndex = new Map();
    links.forEach((l, i) => { if (!linkIndex.has(l.name)) linkIndex.set(l.name, i); });
    links.forEach((l, i) => { if (!jointIndex.has(l.joint)) jointIndex.set(l.joint, i); });
    const linkObject = new Array(links.length).fill(null);
    const objectLink = new Map();
    const visualGroups = [], collisionGroups = [];
    gltf.scene.traverse((o) => {
      const a = gltf.parser.associations.get(o);
      if (!a || a.nodes === undefined) return;
      const node = gltfJson.nodes[a.nodes];
      if (node.extras && node.extras.joint_type !== undefined && linkIndex.has(node.name)) {
        const i = linkIndex.get(node.name);
        if (!linkObject[i]) { linkObject[i] = o; objectLink.set(o, i); nodeLink.set(a.nodes, i); }
      } else if (geometryOf(a.nodes) === 'visual') visualGroups.push(o);
      else if (isCollision(a.nodes)) collisionGroups.push(o);
    });
    const missing = links.filter((l, i) => !linkObject[i]).map((l) => l.name);
    if (missing.length) throw new Error('links without a node in the GLB: ' + missing.slice(0, 5).join(', '));

    // The model node turns Body's Z-up into three.js's Y-up; set exactly so that linkMatrix
    // can undo it exactly.
    const modelNode = linkObject[0].parent;
    const zUpToYUp = new THREE.Matrix4().set(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1);
    const yUpToZUp = new THREE.Matrix4().set(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);
    modelNode.matrixAutoUpdate = false;
    modelNode.matrix.copy(zUpToYUp);
    const offset = links.map((l) => new THREE.Matrix4().fromArray(l.X_PL));
    const q = new Float64Array(links.length);
    // The file's pose: each joint at its initial displacement (joint_angle / joint_displacement).
    const q0 = links.map((l) => ((l.type === 'revolute' || l.type === 'prismatic') && Number.isFinite(l.q0) ? l.q0 : 0));
    q.set(q0);
    const motion = new THREE.Matrix4();
    function place(i) {
      const l = links[i], o = linkObject[i];
      o.matrixAutoUpdate = false;
      o.matrix.copy(offset[i]);
      if (q[i] !== 0 && l.type === 'revolute') {
        const a = new THREE.Vector3(...l.axis).normalize();
        o.matrix.multiply(motion.makeRotationAxis(a, q[i]));
      } else if (q[i] !== 0 && l.type === 'prismatic') {
        o.matrix.multiply(motion.makeTranslation(l.axis[0] * q[i], l.axis[1] * q[i], l.axis[2] * q[i]));
      }
      o.matrixWorldNeedsUpdate = true;
      worldStale = true;
    }
    let worldStale = true;
    links.forEach((l, i) => place(i));

    // Collision geometry is drawn translucent cyan over the visual model.
    const collisionMaterial = new THREE.MeshLambertMaterial({ color: 0x00c8ff, transparent: true, opacity: 0.55, depthWrite: false,
      polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -4 });  // over coincident visual faces
    let collisionLoad = null;
    function loadCollision() {
      collisionLoad ||= parse(gltfJson).then((whole) => {
        const found = [];
        whole.scene.traverse((o) => {
          const a = whole.parser.associations.get(o);
          if (a && a.nodes !== undefined && isCollision(a.nodes)) found.push([o, nodeLink.get(parentNode[a.nodes])]);
        });
        for (const [g, link] of found) {
          if (link === undefined) continue;
          g.traverse((o) => { if (o.isMesh) o.material = collisionMaterial; });
          linkObject[link].add(g);  // its transform was relative to this link's node
          collisionGroups.push(g);
        }
      });
      return collisionLoad;
    }

    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0xffffff);
    scene.add(gltf.scene);
    scene.add(new THREE.HemisphereLight(0xffffff, 0x606060, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(3, 6, 4);
    scene.add(sun);
    scene.updateMatrixWorld(true);
    const bounds = new THREE.Box3().setFromObject(gltf.scene);
    if (bounds.isEmpty()) bounds.setFromCenterAndSize(new THREE.Vector3(), new THREE.Vector3(1, 1, 1));
    const centre = bounds.getCenter(new THREE.Vector3());
    const size = Math.max(bounds.getSize(new THREE.Vector3()).length(), 1e-3);
    const mark = size / 25;  // the size of markers, frames and arrows
    const grid = new THREE.GridHelper(size * 2, 20, 0xbbbbbb, 0xe0e0e0);
    grid.position.set(centre.x, bounds.min.y, centre.z);
    scene.add(grid);

    const canvas = document.getElementById('canvas');
    const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    const camera = new THREE.PerspectiveCamera(40, 1, size / 1000, size * 50);
    const controls = new OrbitControls(camera, canvas);
    const frameUpdaters = [];
    function home() {
      camera.position.copy(centre).add(new THREE.Vector3(size * 0.95, size * 0.7, size * 1.15));
      controls.target.copy(centre);
      controls.update();
    }
    home();
    function render() {
      const w = canvas.clientWidth || 640, h = canvas.clientHeight || 480;
      if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
        renderer.setSize(w, h, false);
        camera.aspect = w / h;
        camera.updateProjectionMatrix();
      }
      for (const f of frameUpdaters) f();
      renderer.render(scene, camera);
    }
    let pending = false;
    function requestRender() {
      if (pending) return;
      pending = true;
      requestAnimationFrame(() => { pending = false; render(); });
    }
    controls.addEventListener('change', requestRender);
    window.addEventListener('resize', requestRender);

    // Overlays, made the first time they are switched on.
    const maxMass = Math.max(1e-12, ...links.map((l) => l.mass || 0));
    const overlayMaterial = (color, opacity) => new THREE.MeshLambertMaterial({ color, transparent: opacity < 1, opacity, depthWrite: opacity >= 1 });
    // A box of uniform density with the tensor's mass and principal moments, about its centre of mass.
    function inertiaBox(i, box, material) {
      const b = new THREE.Mesh(new THREE.BoxGeometry(...box.size.map((v) => Math.max(v, 1e-6))), material);
      b.matrixAutoUpdate = false;
      b.matrix.fromArray(box.X);
      b.renderOrder = 1;
      linkObject[i].add(b);
      return b;
    }
    const makers = {
      frames() {
        return links.map((l, i) => { const h = new THREE.AxesHelper(mark * 2); linkObject[i].add(h); return h; });
      },
      axes() {
        const out = [];
        links.forEach((l, i) => {
          if (!['revolute', 'prismatic', 'pseudo_continuous_track'].includes(l.type)) return;
          const dir = new THREE.Vector3(...l.axis);
          if (dir.lengthSq() === 0) return;
          const arrow = new THREE.ArrowHelper(dir.normalize(), new THREE.Vector3(), mark * 4, l.type === 'prismatic' ? 0x00aa00 : 0xdd00dd, mark, mark * 0.6);
          linkObject[i].add(arrow);
          out.push(arrow);
        });
        return out;
      },
      com() {
        const material = overlayMaterial(0xe00000, 1);
        return links.map((l, i) => {
          const r = mark * 0.4 + mark * 1.2 * Math.cbrt(Math.max(0, l.mass) / maxMass);
          const s = new THREE.Mesh(new THREE.SphereGeometry(r, 16, 12), material);
          s.position.set(...l.com);
          s.renderOrder = 2;
          linkObject[i].add(s);
          return s;
        });
      },
      inertia() {
        const material = overlayMaterial(0xff8800, 0.5);
        const out = [];
        links.forEach((l, i) => { if (l.inertia_box) out.push(inertiaBox(i, l.inertia_box, material)); });
        return out;
      },
      shape_inertia() {
        // The box of the tensor the shapes give at the written mass (bodycheck --fix=geometry's),
        // green with its edges drawn, so that it reads beside or inside the written one's.
        const material = overlayMaterial(0x22aa44, 0.35), edges = new THREE.LineBasicMaterial({ color: 0x117722 });
        const out = [];
        links.forEach((l, i) => {
          if (!l.geometry || !l.geometry.inertia_box) return;
          const b = inertiaBox(i, l.geometry.inertia_box, material);
          b.add(new THREE.LineSegments(new THREE.EdgesGeometry(b.geometry), edges));
          out.push(b);
        });
        return out;
      },
      devices() {
        const out = [];
        for (const d of data.devices) {
          if (d.link < 0 || !linkObject[d.link]) continue;
          const g = new THREE.Group();
          g.matrixAutoUpdate = false;
          g.matrix.fromArray(d.X);
          if (d.camera) {
            // The frustum to a depth of the model's size (the far plane is usually much further).
            const depth = Math.min(d.camera.far, size * 0.4), t = Math.tan(d.camera.fov / 2) * depth;
            const w = d.camera.aspect >= 1 ? t * d.camera.aspect : t, h = d.camera.aspect >= 1 ? t : t / d.camera.aspect;
            const c = [[-w, -h], [w, -h], [w, h], [-w, h]].map(([x, y]) => new THREE.Vector3(x, y, -depth));
            const p = [];
            for (let k = 0; k < 4; ++k) p.push(new THREE.Vector3(), c[k], c[k], c[(k + 1) % 4]);
            g.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(p), new THREE.LineBasicMaterial({ color: 0x0044cc })));
          } else if (d.light) {
            g.add(new THREE.Mesh(new THREE.SphereGeometry(mark * 0.6, 12, 8), new THREE.MeshBasicMaterial({ color: 0xffcc00 })));
            if (d.light.spot) g.add(new THREE.ArrowHelper(new THREE.Vector3(...d.light.direction).normalize(), new THREE.Vector3(), mark * 4, 0xffaa00));
          } else {
            g.add(new THREE.Mesh(new THREE.OctahedronGeometry(mark * 0.6), new THREE.MeshBasicMaterial({ color: 0x008888 })));
          }
          linkObject[d.link].add(g);
          out.push(g);
        }
        return out;
      },
      tracks() {
        // The belt's motion for a positive command (body-format-spec §17): a x n_out, on the
        // top (n_out up) and the bottom (n_out down) of the track's box.
        const out = [];
        links.forEach((l, i) => {
          if (l.type !== 'pseudo_continuous_track') return;
          const a = new THREE.Vector3(...l.axis).normalize();
          const box = l.collision_box || l.visual_box || [-mark, -mark, -mark, mark, mark, mark];
          const mid = new THREE.Vector3((box[0] + box[3]) / 2, (box[1] + box[4]) / 2, (box[2] + box[5]) / 2);
          const up = new THREE.Vector3(0, 0, 1).sub(a.clone().multiplyScalar(a.z)).normalize();
          const half = Math.abs(up.x) * (box[3] - box[0]) / 2 + Math.abs(up.y) * (box[4] - box[1]) / 2 + Math.abs(up.z) * (box[5] - box[2]) / 2;
          const length = Math.max(mark * 3, 0.6 * Math.max(box[3] - box[0], box[4] - box[1], box[5] - box[2]));
          for (const sign of [1, -1]) {
            const n = up.clone().multiplyScalar(sign);
            const dir = a.clone().cross(n).normalize();
            const start = mid.clone().addScaledVector(n, half + mark * 0.5).addScaledVector(dir, -length / 2);
            const arrow = new THREE.ArrowHelper(dir, start, length, 0xff6600, mark * 1.2, mark * 0.8);
            arrow.name = 'belt';
            linkObject[i].add(arrow);
            out.push(arrow);
          }
        });
        return out;
      },
    };
    const toggles = { visual: true, collision: false, frames: false, axes: false, com: false, inertia: false, shape_inertia: false, devices: false, tracks: true };
    const labels = { visual: 'visual', collision: 'collision', frames: 'link frames', axes: 'joint axes', com: 'centres of mass', inertia: 'inertia boxes', shape_inertia: 'inertia boxes from the shapes', devices: 'devices', tracks: 'track belts' };
    const made = {};
    async function setToggle(name, on) {
      if (!(name in toggles)) throw new Error('no toggle ' + name + ' (' + Object.keys(toggles).join(', ') + ')');
      toggles[name] = !!on;
      if (name === 'visual') {
        for (const g of visualGroups) g.visible = toggles.visual;
        for (const b of batches) b.batch.visible = toggles.visual;
      }
      else if (name === 'collision') {
        if (on) await loadCollision();
        for (const g of collisionGroups) g.visible = toggles.collision;
      } else {
        if (on && !made[name]) made[name] = makers[name]();
        for (const o of made[name] || []) o.visible = toggles[name];
      }
      const box = document.getElementById('toggle-' + name);
      if (box) box.checked = toggles[name];
      requestRender();
    }
    const toggleBox = document.getElementById('toggles');
    for (const name of Object.keys(toggles)) {
      const box = el('input', { type: 'checkbox', id: 'toggle-' + name, onchange: (e) => setToggle(name, e.target.checked) });
      box.checked = toggles[name];
      toggleBox.append(el('label', {}, box, ' ' + labels[name]));
    }
    setToggle('tracks', true);

    // Selection: the picked link's own meshes glow blue; the panel says what the link is.
    const ownMeshes = links.map(() => []);
    gltf.scene.traverse((o) => {
      if (!o.isMesh) return;
      let a = o.parent;
      while (a && !objectLink.has(a)) a = a.parent;
      if (a) ownMeshes[objectLink.get(a)].push(o);
    });
    // A large model's visual meshes are drawn as one BatchedMesh per material (one draw call
    // instead of thousands); the meshes stay in the scene, hidden, and give the batch their
    // world matrices each frame, and picking, boxes and selection still use them.
    const BATCH_FROM = 1500;
    const batches = [];
    const visualMeshes = [];
    for (const g of visualGroups) g.traverse((o) => { if (o.isMesh) visualMeshes.push(o); });
    if (visualMeshes.length >= BATCH_FROM && THREE.BatchedMesh) {
      const groups = new Map();
      for (const m of visualMeshes) {
        if (Array.isArray(m.material) || m.material.map || !m.geometry.index) continue;
        const key = m.material.uuid + '|' + Object.keys(m.geometry.attributes).sort().join(',');
        if (!groups.has(key)) groups.set(key, []);
        groups.get(key).push(m);
      }
      for (const meshes of groups.values()) {
        if (meshes.length < 16) continue;
        let vertices = 0, indices = 0;
        for (const m of meshes) { vertices += m.geometry.attributes.position.count; indices += m.geometry.index.count; }
        const batch = new THREE.BatchedMesh(meshes.length, vertices, indices, meshes[0].material);
        batch.frustumCulled = false;  // its bounding sphere would be that of the first pose
        batch.perObjectFrustumCulled = false;
        batch.sortObjects = false;
        const ids = meshes.map((m) => {
          const id = batch.addInstance(batch.addGeometry(m.geometry));
          m.visible = false;
          m.userData.batched = { batch, id };
          return id;
        });
        scene.add(batch);
        batches.push({ batch, meshes, ids });
      }
      frameUpdaters.push(() => {
        scene.updateMatrixWorld();
        for (const b of batches) for (let k = 0; k < b.ids.length; ++k) b.batch.setMatrixAt(b.ids[k], b.meshes[k].matrixWorld);
      });
    }

    let selected = -1;
    const saved = new Map();
    const treeItems = [];
    function select(i) {
      for (const [m, material] of saved) {
        m.material = material;
        if (m.userData.batched) { m.visible = false; m.userData.batched.batch.setVisibleAt(m.userData.batched.id, true); }
      }
      saved.clear();
      if (treeItems[selected]) treeItems[selected].classList.remove('selected');
      selected = i;
      const panel = document.getElementById('panel');
      if (i < 0) { panel.hidden = true; requestRender(); return; }
      for (const m of ownMeshes[i]) {
        if (!m.material || !m.material.emissive || m.material === collisionMaterial) continue;
        saved.set(m, m.material);
        m.material = m.material.clone();
        m.material.emissive = new THREE.Color(0x2244ff);
        m.material.emissiveIntensity = 0.7;
        if (m.userData.batched) { m.visible = true; m.userData.batched.batch.setVisibleAt(m.userData.batched.id, false); }
      }
      if (treeItems[i]) { treeItems[i].classList.add('selected'); treeItems[i].scrollIntoView({ block: 'nearest' }); }
      const l = links[i];
      const I = l.inertia;
      const rows = [
        ['link', l.name], ['parent', l.parent >= 0 ? links[l.parent].name : '(root)'],
        ['joint', l.joint + ' (' + l.type + ')'],
      ];
      if (l.type === 'revolute' || l.type === 'prismatic')
        rows.push(['axis', vec(l.axis)], ['range', '[' + fmt(l.lower) + ', ' + fmt(l.upper) + '] ' + (l.type === 'revolute' ? 'rad' : 'm')], ['position', fmt(q[i]) + (l.type === 'revolute' ? ' rad' : ' m')]);
      rows.push(['mass', fmt(l.mass) + ' kg'], ['centre of mass', vec(l.com) + ' m'],
        ['inertia', vec(I.slice(0, 3)) + '\n' + vec(I.slice(3, 6)) + '\n' + vec(I.slice(6, 9)) + ' kg·m²'],
        ['inertia box', l.inertia_box ? vec(l.inertia_box.size) + ' m' : 'none']);
      const g = l.geometry;
      if (g) {
        const G = g.inertia;
        rows.push(['from the shapes', g.solids + ' ' + g.from + ' solid' + (g.solids === 1 ? '' : 's') + (g.left_out ? ', ' + g.left_out + ' not solid left out' : '') + ", at the link's mass"],
          ['centre of mass', vec(g.com) + ' m'], ['inertia', vec(G.slice(0, 3)) + '\n' + vec(G.slice(3, 6)) + '\n' + vec(G.slice(6, 9)) + ' kg·m²'],
          ['inertia box', g.inertia_box ? vec(g.inertia_box.size) + ' m' : 'none']);
        if (g.fix) {
          // As bodycheck writes them: the numbers read back from its text, shortest form.
          const exact = (v) => '[' + v.map((x) => String(Number(x))).join(', ') + ']';
          const F = g.fix_inertia;
          rows.push(['bodycheck --fix=geometry writes', 'center_of_mass: ' + exact(g.fix_center_of_mass) + '\ninertia: ' + exact(F.slice(0, 3)) + '\n         ' + exact(F.slice(3, 6)) + '\n         ' + exact(F.slice(6, 9))]);
        }
      }
      rows.push(['written at', l.source], ['mass at', l.mass_source], ['inertia at', l.inertia_source]);
      panel.replaceChildren(el('table', {}, ...rows.map(([k, v]) => el('tr', {}, el('td', {}, k), el('td', {}, el('pre', { style: 'margin:0' }, String(v)))))));
      panel.hidden = false;
      requestRender();
    }

    // Picking: a click (not a drag) on a mesh selects its link.
    const raycaster = new THREE.Raycaster();
    let down = null;
    canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
    canvas.addEventListener('pointerup', (e) => {
      if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
      const r = canvas.getBoundingClientRect();
      raycaster.setFromCamera(new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1), camera);
      const hit = raycaster.intersectObject(gltf.scene, true).find((h) => h.object.isMesh && isShown(h.object.userData.batched ? h.object.parent : h.object));
      let a = hit ? hit.object : null;
      while (a && !objectLink.has(a)) a = a.parent;
      select(a ? objectLink.get(a) : -1);
    });
    function isShown(o) {
      for (; o; o = o.parent) if (!o.visible) return false;
      return true;
    }

    // Joint sliders: the model's range; an unlimited revolute joint gets ±180°, an unlimited
    // prismatic one ± the model's size.
    const joints = [];
    const sliders = new Map();
    links.forEach((l, i) => {
      if (l.type !== 'revolute' && l.type !== 'prismatic') return;
      const span = l.type === 'revolute' ? Math.PI : size;
      const min = l.lower === null ? -span : l.lower, max = l.upper === null ? span : l.upper;
      joints.push({ name: l.joint, link: l.name, type: l.type, lower: l.lower, upper: l.upper, min, max, index: i });
    });
    function buildSliders() {
      const box = document.getElementById('joints');
      for (const { min, max, index: i } of joints) {
        const l = links[i];
        const out = el('output');
        const show = () => { out.textContent = l.type === 'revolute' ? (q[i] * 180 / Math.PI).toFixed(1) + '°' : (q[i] * 1000).toFixed(1) + ' mm'; };
        const slider = el('input', { type: 'range', min: String(min), max: String(max), step: String((max - min) / 1000 || 1e-6), value: '0', 'data-joint': l.joint,
          oninput: (e) => { setPosition(i, Number(e.target.value)); } });
        slider.value = String(q[i]);
        sliders.set(i, { slider, show });
        show();
        box.append(el('div', { class: 'joint', title: l.joint + ' on ' + l.name }, el('span', {}, l.joint), slider, out));
      }
    }
    function setPosition(i, value) {
      q[i] = value;
      place(i);
      const s = sliders.get(i);
      if (s) { s.slider.value = String(value); s.show(); }
      if (selected === i) select(i);
      requestRender();
    }
    document.getElementById('reset').addEventListener('click', () => {
      for (const j of joints) setPosition(j.index, q0[j.index]);
      home();
      requestRender();
    });

    // The link tree.
    function buildTree() {
      const childLists = links.map(() => null);
      const tree = document.getElementById('tree');
      links.forEach((l, i) => {
      const label = el('span', { onclick: () => select(i) }, l.name + ' ', el('span', { class: 'jt' }, l.type));
      treeItems[i] = label;
      const li = el('li', {}, label);
      const parentList = l.parent >= 0 ? (childLists[l.parent] ||= treeItems[l.parent].parentElement.appendChild(el('ul'))) : tree;
      parentList.append(li);
    });
    }

    // Findings: clicking one selects its link and shows the diagnostic with its caret. Each
    // starts with its file's name and line:col; the full path is the name's tooltip.
    function buildFindings() {
    const findingList = document.getElementById('findings');
    document.getElementById('finding-count').textContent = '(' + data.findings.length + ')';
    data.findings.forEach((f) => {
      const at = el('span', { class: 'at', title: f.where }, f.at);
      const li = el('li', { class: f.severity, title: f.text }, at, ': ' + f.severity + ': ' + f.message + ' [' + f.rule + ']');
      li.addEventListener('click', () => {
        for (const x of findingList.children) x.classList.remove('selected');
        li.classList.add('selected');
        select(f.link);
        const panel = document.getElementById('panel');
        panel.prepend(el('pre', {}, f.text));
        panel.hidden = false;
      });
      findingList.append(li);
    });
    }

    function find(name) {
      const i = linkIndex.has(name) ? linkIndex.get(name) : jointIndex.has(name) ? jointIndex.get(name) : -1;
      if (i < 0) throw new Error('no link or joint named ' + name);
      return i;
    }
    Object.assign(api, {
      joints: () => joints.map(({ index, ...j }) => ({ ...j, value: q[index] })),
      links: () => links.map((l) => l.name),
      link: (name) => ({ ...links[find(name)] }),
      drawnBox(name) {
        // The box of the link's own visual meshes as drawn, in Body's Z-up world.
        scene.updateMatrixWorld();
        worldStale = false;
        const box = new THREE.Box3();
        for (const m of ownMeshes[find(name)]) {
          let visual = false;
          for (let a = m; a && !visual; a = a.parent) visual = visualGroups.includes(a);
          if (visual) box.expandByObject(m);
        }
        if (box.isEmpty()) return null;
        box.applyMatrix4(yUpToZUp);
        return [...box.min.toArray(), ...box.max.toArray()];
      },
      setJoint(name, value) {
        const i = find(name);
        if (links[i].type !== 'revolute' && links[i].type !== 'prismatic') throw new Error(name + ' is ' + links[i].type);
        if (!Number.isFinite(value)) throw new Error('the position of ' + name + ' is not a finite number');
        setPosition(i, value);
      },
      linkMatrix(name) {
        // three.js's own update, as a render does it (a moved link passes its change down).
        if (worldStale) { scene.updateMatrixWorld(); worldStale = false; }
        const o = linkObject[find(name)];
        return Array.from(new THREE.Matrix4().multiplyMatrices(yUpToZUp, o.matrixWorld).elements);
      },
      findings: () => data.findings.map((f) => ({ ...f, link: f.link >= 0 ? links[f.link].name : null })),
      toggles: () => ({ ...toggles }),
      setToggle,
      select: (name) => select(name === null ? -1 : find(name)),
      reset: () => document.getElementById('reset').click(),
      render() { render(); return canvas.toDataURL('image/png'); },
      batched: () => batches.reduce((n, b) => n + b.ids.length, 0),
      camera: () => ({ position: camera.position.toArray(), target: controls.target.toArray() }),
    });

    // --serve: follow the model; an error is shown over the last good model.
    if (data.serve) {
      let generation = null;
      const error = document.getElementById('error');
      const poll = async () => {
        try {
          const status = await (await fetch(data.serve, { cache: 'no-store' })).json();
          if (generation === null) generation = status.generation;
          else if (status.generation !== generation) { location.reload(); return; }
          error.textContent = status.error;
          error.hidden = !status.error;
          api.serveStatus = status;
        } catch (e) {
          error.textContent = 'bodyview --serve is not answering';
          error.hidden = false;
        }
        setTimeout(poll, 300);
      };
      poll();
    }

    // The URL fragment sets toggles and joints: #collision=1&q.ARM=90 (degrees for a revolute
    // joint, millimetres for a prismatic one, as the sliders show them). Whatever it holds, a
    // part that names nothing, or no number, is skipped with a console message; a position
    // outside the joint's range is clamped to it.
    api.fragmentMessages = [];
    const fragmentMessage = (text) => { api.fragmentMessages.push(text); console.warn('bodyview: URL fragment: ' + text); };
    async function applyFragment(fragment) {
      for (const part of fragment.replace(/^#/, '').split('&')) {
        if (!part) continue;
        const eq = part.indexOf('=');
        let key, value;
        try {
          key = decodeURIComponent(eq < 0 ? part : part.slice(0, eq));
          value = eq < 0 ? '' : decodeURIComponent(part.slice(eq + 1));
        } catch (e) {
          fragmentMessage('"' + part.slice(0, 80) + '" is not URI-encoded text; skipped');
          continue;
        }
        const shown = JSON.stringify(key.slice(0, 80));
        if (key.startsWith('q.')) {
          const name = key.slice(2);
          const j = joints.find((x) => x.name === name) || joints.find((x) => x.link === name);
          if (!j) { fragmentMessage(shown + ': no movable joint or link of that name; skipped'); continue; }
          const number = value.trim() === '' ? NaN : Number(value);
          if (!Number.isFinite(number)) { fragmentMessage(shown + ': ' + JSON.stringify(value.slice(0, 40)) + ' is not a number; skipped'); continue; }
          let position = j.type === 'revolute' ? number * Math.PI / 180 : number / 1000;
          const lower = j.lower === null ? -Infinity : j.lower, upper = j.upper === null ? Infinity : j.upper;
          if (position < lower || position > upper) {
            position = Math.min(Math.max(position, lower), upper);
            fragmentMessage(shown + ': ' + value + ' is outside the joint range; clamped to ' +
              (j.type === 'revolute' ? (position * 180 / Math.PI).toFixed(1) + '°' : (position * 1000).toFixed(1) + ' mm'));
          }
          setPosition(j.index, position);
        } else if (key in toggles) {
          if (!['0', '1', 'true', 'false', 'on', 'off'].includes(value)) { fragmentMessage(shown + ': ' + JSON.stringify(value.slice(0, 40)) + ' is not 0 or 1; skipped'); continue; }
          await setToggle(key, value === '1' || value === 'true' || value === 'on');
        } else {
          fragmentMessage(shown + ': not a toggle (' + Object.keys(toggles).join(', ') + ') or q.JOINT; skipped');
        }
      }
    }
    await applyFragment(location.hash);
    window.addEventListener('hashchange', () => { applyFragment(location.hash); });

    timings.setup = performance.now();
    render();
    timings.rendered = performance.now();
    api.firstFrameMs = performance.now();  // since the navigation started
    // The side panel after the first frame: on a large model its layout costs more than the frame.
    await new Promise((resolve) => setTimeout(resolve, 0));
    buildTree();
    buildSliders();
    buildFindings();
    timings.panels = performance.now();
    resolveReady({ links: links.length, joints: joints.length, firstFrameMs: api.firstFrameMs });
  }

  main().catch((e) => {
    const error = document.getElementById('error');
    error.textContent = 'bodyview: ' + (e && e.stack ? e.stack : e);
    error.hidden = false;
    console.error(e);
    rejectReady(e);
  });
})();
