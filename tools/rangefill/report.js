// report.html of `rangefill bench`: the 3D view of each hole (three.js, inlined before this
// script) and the depth images in colour. For the browser test, document.body.dataset says how
// many holes were drawn in 3D (views), how many images were coloured (images) and how many
// errors the page met (errors, counted by the handler at the top of the page).
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('bench-views').textContent);

  function bytes(text) {
    return Uint8Array.from(atob(text), (c) => c.charCodeAt(0)).buffer;
  }
  const floats = (text) => new Float32Array(bytes(text));
  const indices = (text) => new Uint32Array(bytes(text));

  // Colour maps: viridis (depth, distance) and blue-white-red (differences), t in [0, 1].
  const VIRIDIS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const DIVERGING = [[33, 102, 172], [247, 247, 247], [178, 24, 43]];
  function ramp(stops, t) {
    const x = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
    const i = Math.min(Math.floor(x), stops.length - 2);
    const f = x - i;
    return stops[i].map((v, k) => v + f * (stops[i + 1][k] - v));
  }
  function gradient(stops) {
    return 'linear-gradient(to right,' +
        stops.map((c, i) => `rgb(${c}) ${(100 * i) / (stops.length - 1)}%`).join(',') + ')';
  }

  // --- The 3D view: one WebGL context for every hole --------------------------------------
  const viewer = document.getElementById('viewer');
  const box = viewer.querySelector('.canvas');
  const WIDTH = 480, HEIGHT = 360;  // the size of .canvas in the page's style
  const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(WIDTH, HEIGHT);
  box.appendChild(renderer.domElement);
  const camera = new THREE.PerspectiveCamera(35, WIDTH / HEIGHT, 1e-3, 1e3);
  const light = new THREE.DirectionalLight(0xffffff, 0.7);
  camera.add(light);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xffffff);
  const render = () => renderer.render(scene, camera);
  controls.addEventListener('change', render);
  const showTruth = document.getElementById('viewer-truth');
  let current = {hole: 0, method: 0};

  function geometry(mesh, colours) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(floats(mesh.p), 3));
    g.setIndex(new THREE.BufferAttribute(indices(mesh.t), 1));
    if (colours) g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    g.computeVertexNormals();
    g.computeBoundingSphere();
    return g;
  }

  // Whether the last drawing covers some of the view (it is not all background).
  function drawn() {
    const gl = renderer.getContext();
    const pixels = new Uint8Array(4 * gl.drawingBufferWidth * gl.drawingBufferHeight);
    gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE,
                  pixels);
    return pixels.some((value, i) => i % 4 !== 3 && value < 250);
  }

  // Draws `method` on `hole`; returns whether WebGL drew without an error.
  function show(h, m) {
    const hole = data.holes[h], method = hole.methods[m];
    current = {hole: h, method: m};
    scene.traverse((object) => {  // the last hole's buffers freed on the GPU
      if (object.geometry) object.geometry.dispose();
      if (object.material) object.material.dispose();
    });
    scene.remove(...scene.children);
    scene.add(camera, new THREE.AmbientLight(0xffffff, 0.45));
    scene.add(new THREE.Mesh(geometry(hole.surroundings), new THREE.MeshLambertMaterial(
        {color: 0xc8c8c8, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1})));
    const truth = geometry(hole.truth);
    if (showTruth.checked) {
      scene.add(new THREE.LineSegments(new THREE.WireframeGeometry(truth),
                                       new THREE.LineBasicMaterial({color: 0x111111})));
    }
    if (method.patch) {
      const distance = floats(method.d);
      const colours = new Float32Array(3 * distance.length);
      distance.forEach((d, i) => colours.set(ramp(VIRIDIS, d / hole.scale).map((c) => c / 255), 3 * i));
      scene.add(new THREE.Mesh(geometry(method.patch, colours), new THREE.MeshLambertMaterial(
          {vertexColors: THREE.VertexColors, side: THREE.DoubleSide})));
    }
    // Framed on the truth, seen along its mean normal.
    const sphere = truth.boundingSphere, normals = truth.getAttribute('normal');
    const facing = new THREE.Vector3();
    for (let i = 0; i < normals.count; ++i) {
      facing.x += normals.getX(i), facing.y += normals.getY(i), facing.z += normals.getZ(i);
    }
    if (facing.lengthSq() === 0) facing.set(0, 0, 1);
    const distance = 4.5 * Math.max(sphere.radius, 1e-9);
    camera.position.copy(sphere.center).addScaledVector(facing.normalize(), distance);
    camera.near = distance / 100;
    camera.far = distance * 100;
    camera.updateProjectionMatrix();
    controls.target.copy(sphere.center);
    controls.update();
    render();
    viewer.querySelector('.title').textContent = hole.title + ': ' + method.name +
        (method.patch ? ', H ' + method.h + ' d_m' : ' (open)');
    viewer.querySelector('.legend-bar').style.background = gradient(VIRIDIS);
    viewer.querySelector('.legend-high').textContent = hole.scale.toPrecision(2) + ' d_m';
    viewer.querySelectorAll('.methods button').forEach((b, i) => b.classList.toggle('on', i === m));
    return renderer.getContext().getError() === 0;
  }

  function choose(h) {
    const buttons = viewer.querySelector('.methods');
    buttons.textContent = '';
    data.holes[h].methods.forEach((method, m) => {
      const button = document.createElement('button');
      button.textContent = method.name;
      button.addEventListener('click', () => show(h, m));
      buttons.appendChild(button);
    });
    show(h, data.holes[h].best);
    viewer.classList.remove('closed');
  }
  showTruth.addEventListener('change', () => show(current.hole, current.method));
  viewer.querySelector('.close').addEventListener('click', () => viewer.classList.toggle('closed'));
  document.querySelectorAll('[data-hole]').forEach((element) => element.addEventListener('click',
      () => choose(Number(element.dataset.hole))));

  // Every hole and method drawn once: a hole counts as a view when every method drew without an
  // error and its best method's drawing shows something.
  let views = 0;
  data.holes.forEach((hole, h) => {
    let ok = true;
    hole.methods.forEach((method, m) => ok = show(h, m) && ok);
    views += ok && show(h, hole.best) && drawn();
  });
  document.body.dataset.views = views;
  // The hole the address names (report.html#hole-12), else the first.
  const named = /^#hole-(\d+)$/.exec(window.location.hash);
  if (data.holes.length > 0) choose(named && named[1] < data.holes.length ? Number(named[1]) : 0);

  // --- Depth images: viridis for depth, a difference from the first restoration ------------
  let coloured = 0;
  function pixels(image) {
    const canvas = document.createElement('canvas');
    canvas.width = image.naturalWidth;
    canvas.height = image.naturalHeight;
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    return {canvas, context, values: context.getImageData(0, 0, canvas.width, canvas.height)};
  }
  function replace(image, canvas) {
    canvas.className = image.className;
    canvas.title = image.alt;
    image.replaceWith(canvas);
    ++coloured;
    document.body.dataset.images = coloured;
  }
  document.querySelectorAll('.hole').forEach((section) => {
    const images = [...section.querySelectorAll('img.depth')];
    const loaded = images.map((image) => image.decode().then(() => image));
    Promise.all(loaded).then(() => {
      const restorations = images.filter((image) => image.dataset.kind === 'restored');
      const reference = restorations.length ? pixels(restorations[0]).values.data : null;
      images.forEach((image) => {
        const {canvas, context, values} = pixels(image);
        const data = values.data;
        if (image.dataset.kind === 'difference-source') {
          // The difference from the first restoration, scaled to its largest.
          let largest = 1;
          for (let i = 0; i < data.length; i += 4) largest = Math.max(largest, Math.abs(data[i] - reference[i]));
          for (let i = 0; i < data.length; i += 4) {
            const rgb = ramp(DIVERGING, 0.5 + (data[i] - reference[i]) / (2 * largest));
            data.set(rgb, i);
          }
          const caption = image.closest('figure').querySelector('figcaption');
          caption.textContent += ' (±' + largest + ' of 255)';
        } else if (image.dataset.kind !== 'mask') {
          for (let i = 0; i < data.length; i += 4) {
            if (image.dataset.kind === 'depth' && data[i] === 0) continue;  // unknown: black
            data.set(ramp(VIRIDIS, data[i] / 255), i);
          }
        }
        context.putImageData(values, 0, 0);
        replace(image, canvas);
      });
    });
  });
})();
