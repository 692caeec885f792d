// The page's side of softbody in the browser (index.html): reads the address's parameters into
// the app's command line, checks that the browser can run it, picks the build, shows progress
// and errors, and hands the app its canvas. Everything else is the app's own C++.
'use strict';

(function () {
  const status = document.getElementById('status');
  const output = document.getElementById('output');
  const canvas = document.getElementById('canvas');

  function show(text, isError) {
    status.textContent = text;
    status.className = isError ? 'error' : '';
    status.style.display = text ? 'block' : 'none';
  }
  function fail(text) {
    show(text, true);
    console.error('softbody: ' + text);
  }

  // --- The command line, from the address -------------------------------------------------
  const params = new URLSearchParams(location.search);
  const own = new Set(['build', 'kernel', 'command']);
  const command = params.get('command') || 'run';
  const args = [command];
  for (const [name, value] of params) {
    if (own.has(name)) continue;
    args.push('--' + name.replace(/_/g, '-'));
    if (value !== '') args.push(value);
  }
  // A run at a given --size gets a canvas of that size; otherwise the canvas fills the window.
  const size = /^(\d+)x(\d+)$/.exec(params.get('size') || '');
  if (size) {
    canvas.style.width = size[1] + 'px';
    canvas.style.height = size[2] + 'px';
  }
  if (command !== 'run') {  // a command that only prints: its output on the page
    canvas.style.display = 'none';
    output.style.display = 'block';
  }

  // --- What the browser must have ----------------------------------------------------------
  // A module with one SIMD instruction (v128.const): browsers without WebAssembly SIMD refuse it.
  const simd = new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 22, 1,
                               20, 0, 253, 12, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 11]);
  if (typeof WebAssembly !== 'object' || !WebAssembly.validate(simd)) {
    fail('softbody needs WebAssembly with SIMD: a recent Chrome, Edge, Firefox or Safari (16.4 or later).');
    return;
  }
  if (command === 'run' && !document.createElement('canvas').getContext('webgl2')) {
    fail('softbody needs WebGL 2, which this browser does not offer (or has turned off).');
    return;
  }

  // --- Which build: threads need a cross-origin isolated page (SharedArrayBuffer) ----------
  let build = params.get('build') || (self.crossOriginIsolated ? 'threads' : 'single');
  if (build !== 'single' && build !== 'threads') {
    fail("build=" + build + ": expected 'single' or 'threads'");
    return;
  }
  if (build === 'threads' && !self.crossOriginIsolated) {
    fail('build=threads needs a cross-origin isolated page: serve it with the headers ' +
         'Cross-Origin-Opener-Policy: same-origin and Cross-Origin-Embedder-Policy: require-corp ' +
         '(web/serve.py sends them), or leave build out to run on one thread.');
    return;
  }
  console.log('softbody: ' + (build === 'threads' ? 'the threaded build (' + navigator.hardwareConcurrency +
              ' hardware threads)' : 'the one-thread build') + ': ' + args.join(' '));

  const kernel = params.get('kernel');
  window.Module = {
    canvas: canvas,
    arguments: args,
    preRun: [function () {
      if (kernel) ENV.SOFTBODY_KERNEL = kernel;  // read by the pair kernel (getenv)
    }],
    print: function (text) {
      console.log(text);
      if (command !== 'run') output.textContent += text + '\n';
    },
    printErr: function (text) {
      console.error(text);
      if (command !== 'run') output.textContent += text + '\n';
      // The app's one-line errors end it (a note does not): say so on the page too.
      else if (/^softbody: /.test(text) && !/^softbody: note: /.test(text)) show(text, true);
    },
    setStatus: function (text) {
      // "Downloading data... (done/total)" while the assets arrive; "" when running.
      const m = /\((\d+)\/(\d+)\)/.exec(text);
      show(m ? 'Loading softbody\u2026 ' + Math.round(100 * m[1] / Math.max(1, m[2])) + '%' : text, false);
    },
    onRuntimeInitialized: function () { show('', false); },
    // main() has returned: for a command that prints, it has finished (`run` goes on in the
    // page's animation frames). Scripts that drive the page (tests/web) wait for this.
    postRun: [function () { window.Module.mainReturned = true; }],
    onAbort: function (what) { fail('softbody stopped: ' + what); },
  };
  window.addEventListener('error', function (event) { fail(String(event.message || event)); });

  const script = document.createElement('script');
  script.src = build === 'threads' ? 'softbody-threads.js' : 'softbody.js';
  script.onerror = function () { fail('cannot load ' + script.src + ' from the server'); };
  document.body.appendChild(script);
})();
