// Browser tests of the viewer page in headless Chromium (Debian's chromium, driven by
// playwright-core from web/package-lock.json). CTest runs one case per invocation:
//   node viewer_browser_test.mjs view   --cli DRVSLAM --run RUN_DIR [--screenshot PNG]
//   node viewer_browser_test.mjs report --cli DRVSLAM --run RUN_DIR [--screenshot PNG]
//     (the report twice: with WebGL, then in a browser without it, screenshot PNG's name with
//     "-nowebgl" before ".png")
//   node viewer_browser_test.mjs live   --cli DRVSLAM --dataset SEQ --out OUT_DIR [--screenshot PNG]
// A case exits 0 when every check holds, else 1 after printing what failed.
import { spawn } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';

const kChromium = process.env.DRVSLAM_CHROMIUM ?? '/usr/bin/chromium';
// WebGL without a GPU: SwiftShader, the software renderer Chromium ships.
const kChromiumArgs = ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
                       '--no-sandbox', '--disable-dev-shm-usage'];
// No WebGL at all: no GPU and no software renderer for it, as on a machine without either.
const kNoWebglArgs = ['--disable-gpu', '--disable-software-rasterizer', '--no-sandbox',
                      '--disable-dev-shm-usage'];

function parseArgs(argv) {
  const args = { case: argv[0] };
  for (let i = 1; i < argv.length; i += 2) args[argv[i].replace(/^--/, '')] = argv[i + 1];
  return args;
}

const failures = [];
function check(condition, what) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${what}`);
  if (!condition) failures.push(what);
}

// Poses in a TUM trajectory file (lines that are neither empty nor comments).
function countPoses(file) {
  if (!existsSync(file)) return 0;
  return readFileSync(file, 'utf8').split('\n').filter((l) => l.trim() && !l.startsWith('#')).length;
}

// The vertex count in a PLY header.
function plyVertices(file) {
  if (!existsSync(file)) return 0;
  const header = readFileSync(file).subarray(0, 1024).toString('latin1');
  const match = header.match(/element vertex (\d+)/);
  return match ? Number(match[1]) : 0;
}

// Starts a drvslam command and resolves with the URL it prints ("viewer: http://...").
function startServing(cli, args) {
  const child = spawn(cli, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  const url = new Promise((resolve, reject) => {
    const onData = (data) => {
      output += data.toString();
      const match = output.match(/viewer: (http:\/\/127\.0\.0\.1:\d+\/)/);
      if (match) resolve(match[1]);
    };
    child.stdout.on('data', onData);
    child.stderr.on('data', onData);
    child.on('exit', (code) => reject(new Error(`${cli} ${args.join(' ')} exited ${code}:\n${output}`)));
    // unref: a pending timeout must not keep node running after the checks.
    setTimeout(() => reject(new Error(`no viewer URL within 60 s:\n${output}`)), 60000).unref();
  });
  return { child, url, output: () => output };
}

async function openBrowser(args = kChromiumArgs) {
  const browser = await chromium.launch({ executablePath: kChromium, args });
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const errors = [];
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(message.text());
  });
  page.on('pageerror', (error) => errors.push(String(error)));
  return { browser, page, errors };
}

// Runs in the page (page.evaluate sends its text, so it may use nothing from this module): the
// grey-level variance of the PNG `base64` when given, else of the canvas with id `canvasId`.
async function greyVarianceInPage({ base64, canvasId }) {
  let source;
  if (base64) {
    source = new Image();
    source.src = `data:image/png;base64,${base64}`;
    await source.decode();
  } else {
    source = document.getElementById(canvasId);
  }
  const canvas = document.createElement('canvas');
  canvas.width = source.width;
  canvas.height = source.height;
  const g = canvas.getContext('2d');
  g.drawImage(source, 0, 0);
  const { data } = g.getImageData(0, 0, canvas.width, canvas.height);
  let sum = 0, sum2 = 0;
  const n = data.length / 4;
  for (let i = 0; i < data.length; i += 4) {
    const v = (data[i] + data[i + 1] + data[i + 2]) / 3;
    sum += v;
    sum2 += v * v;
  }
  return sum2 / n - (sum / n) ** 2;
}

// The screenshot's grey-level variance, computed in the page from the PNG (no image library).
async function screenshotVariance(page, file) {
  const png = await page.screenshot({ path: file });
  return page.evaluate(greyVarianceInPage, { base64: png.toString('base64') });
}

// Variance of the 3-D canvas alone (WebGL, preserveDrawingBuffer), so the map itself is drawn.
async function mapCanvasVariance(page) {
  return page.evaluate(greyVarianceInPage, { canvasId: 'view3d' });
}

// The panels that need no WebGL: the figures, the stage chart in its two groups (per frame of
// the tracking thread, per keyframe of the other threads, names in full) and the 2-D plots.
async function checkPanels(page) {
  const p = await page.evaluate(() => {
    const names = (group) => [...document.querySelectorAll(`[data-group="${group}"] .name`)];
    return {
      figures: document.querySelectorAll('#figures tr').length,
      groups: [...document.querySelectorAll('#stages .stage-group')].map((g) => g.dataset.group),
      frame: names('frame').map((n) => n.textContent),
      keyframe: names('keyframe').map((n) => n.textContent),
      clipped: [...document.querySelectorAll('#stages .name')]
        .filter((n) => n.scrollWidth > n.clientWidth + 1).map((n) => n.textContent),
      plotsShown: !document.getElementById('plots').hidden,
      loops: document.getElementById('loops').textContent,
    };
  });
  check(p.figures >= 5, `figures table filled (${p.figures} rows)`);
  check(p.groups.join(',') === 'frame,keyframe', `stage chart in two groups: ${p.groups.join(', ')}`);
  check(p.frame[0] === 'total' && p.frame.includes('tracking') && !p.frame.includes('local_mapping'),
        `per-frame group: ${p.frame.join(' ')}`);
  check(p.keyframe.includes('local_mapping') && p.keyframe.includes('dense_keyframe') &&
        !p.keyframe.includes('total'), `per-keyframe group: ${p.keyframe.join(' ')}`);
  check(p.clipped.length === 0, `stage names in full (clipped: ${p.clipped.join(' ')})`);
  check(p.loops.startsWith('loop closures'), `loop closures panel: "${p.loops}"`);
  check(p.plotsShown, '2-D plots shown');
  for (const id of ['plot-trajectory', 'plot-errors']) {
    const variance = await page.evaluate(greyVarianceInPage, { canvasId: id });
    check(variance > 5, `${id} drawn (grey-level variance ${variance.toFixed(1)})`);
  }
}

// The checks of a finished run, whether served (view) or from report.html.
async function checkFinishedRun(page, errors, runDir, screenshot, budget) {
  await page.waitForFunction(() => window.drvslamViewer?.ready === true, null, { timeout: 30000 });
  await page.waitForTimeout(500);  // a few animation frames
  const v = await page.evaluate(() => ({ ...window.drvslamViewer }));
  console.log(`page counts: ${JSON.stringify(v)}`);
  check(v.failure === null, `page loaded its data (${v.failure})`);
  check(v.webgl === true, `3-D view has WebGL (${v.webglProblem})`);
  await checkPanels(page);
  const poses = countPoses(path.join(runDir, 'CameraTrajectory.txt'));
  check(poses > 0 && v.poses === poses, `trajectory poses drawn ${v.poses} = CameraTrajectory.txt ${poses}`);
  const keyframes = countPoses(path.join(runDir, 'KeyFrameTrajectory.txt'));
  check(keyframes > 0 && v.keyframes === keyframes, `keyframes drawn ${v.keyframes} = KeyFrameTrajectory.txt ${keyframes}`);
  const sparse = plyVertices(path.join(runDir, 'sparse_map.ply'));
  check(sparse > 0 && v.mapPoints === sparse, `map points drawn ${v.mapPoints} = sparse_map.ply ${sparse}`);
  const dense = plyVertices(path.join(runDir, 'dense_map.ply'));
  check(dense > 0 && v.denseTotal === dense && v.densePoints > 0 && v.densePoints <= dense,
        `dense points drawn ${v.densePoints} of ${v.denseTotal}, dense_map.ply ${dense}`);
  const note = await page.textContent('#notes');
  if (budget < dense) {
    check(v.densePoints === budget && note.includes(`showing ${budget} of ${dense} points`),
          `decimated to the budget ${budget} and said so: "${note}"`);
  }
  // The synthetic room has a floor, so the run wrote map.yaml + map.pgm; the page draws every
  // cell of the PGM.
  const pgm = readFileSync(path.join(runDir, 'map.pgm'));
  const [, pgmWidth, pgmHeight] = pgm.toString('latin1').match(/^P5\s+(?:#[^\n]*\n\s*)*(\d+)\s+(\d+)/);
  const occupied = [...pgm.subarray(pgm.length - pgmWidth * pgmHeight)].filter((value) => value === 0).length;
  check(v.gridCells === pgmWidth * pgmHeight && v.gridOccupied === occupied && occupied > 0,
        `grid drawn: ${v.gridCells} cells (${v.gridOccupied} occupied) = map.pgm ${pgmWidth} x ${pgmHeight} (${occupied} occupied)`);
  check(v.groundTruthPoses > 0 && v.errorSamples === poses,
        `ground truth drawn (${v.groundTruthPoses} poses), error over time for every pose (${v.errorSamples})`);
  // The frame log the setup wrote (one line per tracked frame) is drawn beside the error, with a
  // tick for every keyframe it made.
  const logLines = readFileSync(path.join(runDir, 'frames.tsv'), 'utf8').trim().split('\n').length - 1;
  check(logLines > 0 && v.eventFrames === logLines, `frame log events drawn ${v.eventFrames} = frames.tsv ${logLines}`);
  check(v.keyframeTicks > 0, `keyframe ticks drawn (${v.keyframeTicks})`);
  const mapVariance = await mapCanvasVariance(page);
  check(mapVariance > 5, `3-D view not blank (grey-level variance ${mapVariance.toFixed(1)})`);
  const variance = await screenshotVariance(page, screenshot);
  check(variance > 20, `screenshot not blank (grey-level variance ${variance.toFixed(1)}) -> ${screenshot}`);
  check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
}

async function viewCase(args) {
  // A budget below the test map's size, so the decimation and its note are checked.
  const budget = 20000;
  const server = startServing(args.cli, ['view', args.run, '--port', '0', '--dense-budget', String(budget)]);
  const { browser, page, errors } = await openBrowser();
  try {
    await page.goto(await server.url);
    await checkFinishedRun(page, errors, args.run, args.screenshot ?? path.join(args.run, 'view.png'), budget);
  } finally {
    await browser.close();
    server.child.kill('SIGTERM');
  }
}

async function reportCase(args) {
  const report = path.join(args.run, 'report.html');
  const made = spawn(args.cli, ['report', args.run, '--out', report], { stdio: 'inherit' });
  const code = await new Promise((resolve) => made.on('exit', resolve));
  check(code === 0, `drvslam report exit status ${code}`);
  const { browser, page, errors } = await openBrowser();
  // Offline: any request that is not the file itself fails the test.
  const fetched = [];
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') || url.startsWith('data:')) return route.continue();
    fetched.push(url);
    return route.abort();
  });
  try {
    await page.goto(`file://${path.resolve(report)}`);
    await checkFinishedRun(page, errors, args.run, args.screenshot ?? path.join(args.run, 'report.png'),
                           Infinity);
    check(fetched.length === 0, `report fetched nothing from the network (${fetched.join(', ')})`);
  } finally {
    await browser.close();
  }
  await checkReportWithoutWebgl(report, args.screenshot ?? path.join(args.run, 'report.png'));
}

// The report in a browser that has no WebGL: the 3-D panel says why, every other panel works.
async function checkReportWithoutWebgl(report, screenshot) {
  const { browser, page, errors } = await openBrowser(kNoWebglArgs);
  try {
    await page.goto(`file://${path.resolve(report)}`);
    await page.waitForFunction(() => window.drvslamViewer?.ready === true, null, { timeout: 30000 });
    const v = await page.evaluate(() => ({ ...window.drvslamViewer }));
    console.log(`without WebGL: ${JSON.stringify(v)}`);
    check(v.failure === null, `without WebGL: page loaded its data (${v.failure})`);
    check(v.webgl === false && typeof v.webglProblem === 'string',
          `without WebGL: page knows (${v.webglProblem})`);
    const message = await page.textContent('#view3d-message').catch(() => '');
    check(message.includes('3-D view unavailable') && message.includes(v.webglProblem ?? '?'),
          `without WebGL: the 3-D panel says why: "${message.slice(0, 80)}..."`);
    check(await page.isVisible('#view3d-message'), 'without WebGL: the note is visible');
    await checkPanels(page);
    const shot = screenshot.replace(/(\.png)?$/, '-nowebgl.png');
    const variance = await screenshotVariance(page, shot);
    check(variance > 20, `without WebGL: screenshot not blank (variance ${variance.toFixed(1)}) -> ${shot}`);
    check(errors.length === 0, `without WebGL: no console errors (${errors.join(' | ')})`);
  } finally {
    await browser.close();
  }
}

async function liveCase(args) {
  const run = startServing(args.cli, ['run', '--dataset', args.dataset, '--out', args.out,
                                      '--viewer', '0']);
  const exited = new Promise((resolve) => run.child.on('exit', resolve));
  let running = true;
  exited.then(() => { running = false; });
  const { browser, page, errors } = await openBrowser();
  try {
    await page.goto(await run.url);
    // Samples the page while the run goes on: the pose count must grow between samples.
    const samples = [];
    const deadline = Date.now() + 180000;  // a hung run fails here, not at CTest's timeout
    while (running && Date.now() < deadline) {
      const v = await page.evaluate(() => ({ ...window.drvslamViewer }));
      if (!running || v.finished) break;
      if (v.poses > 0 && (samples.length === 0 || v.poses !== samples[samples.length - 1].poses)) {
        samples.push(v);
      }
      await page.waitForTimeout(100);
    }
    console.log(`pose counts seen while running: ${samples.map((v) => v.poses).join(' ')}`);
    check(samples.length > 0 && samples[0].mode === 'live', 'page in live mode');
    check(samples.length >= 3 && samples.every((v, i) => i === 0 || v.poses > samples[i - 1].poses),
          `pose updates arrived while the run went on (${samples.length} growing samples)`);
    if (samples.length >= 2) {
      check(samples[samples.length - 1].lastFrameId > samples[0].lastFrameId,
            `frame ids advanced: ${samples[0].lastFrameId} -> ${samples[samples.length - 1].lastFrameId}`);
    }
    await page.waitForFunction(() => window.drvslamViewer.finished === true, null, { timeout: 120000 });
    const last = await page.evaluate(() => ({ ...window.drvslamViewer }));
    console.log(`last: ${JSON.stringify(last)}`);
    check(last.images > 0, `current images arrived (${last.images})`);
    // A synthetic run tracked throughout: every pose is verified, and the page says so.
    check(last.localizationQuality === 'verified', `localization quality shown (${last.localizationQuality})`);
    check(last.mapPoints > 0 && last.keyframes > 0, `map points (${last.mapPoints}) and keyframes (${last.keyframes}) arrived`);
    check(last.densePoints > 0, `dense chunks arrived (${last.densePoints} points)`);
    const code = await exited;
    check(code === 0, `drvslam run exit status ${code}`);
    const poses = countPoses(path.join(args.out, 'CameraTrajectory.txt'));
    check(last.poses === poses, `every tracked pose reached the page: ${last.poses} = CameraTrajectory.txt ${poses}`);
    if (args.screenshot) await page.screenshot({ path: args.screenshot });
    check(errors.length === 0, `no console errors (${errors.join(' | ')})`);
  } finally {
    await browser.close();
    if (running) run.child.kill('SIGTERM');
  }
}

const args = parseArgs(process.argv.slice(2));
const cases = { view: viewCase, report: reportCase, live: liveCase };
if (!cases[args.case]) {
  console.error(`usage: viewer_browser_test.mjs view|report|live --cli DRVSLAM ...`);
  process.exit(2);
}
try {
  await cases[args.case](args);
} catch (error) {
  failures.push(String(error));
  console.error(error);
}
if (failures.length) {
  console.error(`${failures.length} check(s) failed`);
  process.exit(1);
}
console.log('all checks passed');
