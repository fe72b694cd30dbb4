// Sorts the collection page's robots table by clicking its headers, as a user does, in headless Chromium
// (cdp.mjs), for crates/cli/tests/collection.rs.
//
// node sort_table.mjs CHROMIUM URL
//
// Opens URL (index.html), then for each column header: a click (real mouse events), the column's sort keys
// (the cells' data-v) top to bottom and the header's aria-sort; a second click, the same again. Prints
// one JSON object: { columns: [{ title, type, first: { sort, keys }, second: { sort, keys } }], console }.

import { openTab } from "./cdp.mjs";

const [chromium, url] = process.argv.slice(2);
const { page, evaluate, console, finish } = await openTab(chromium, { width: 1280, height: 900, timeoutMs: 60_000 });

try {
  await page("Page.navigate", { url });
  let ready = false;
  for (let i = 0; i < 300 && !ready; i++) {
    ready = await evaluate("document.readyState === 'complete' && !!document.getElementById('robots')").catch(() => false);
    if (!ready) await new Promise((r) => setTimeout(r, 20));
  }
  if (!ready) finish({ error: "no robots table", console }, 1);
  const count = await evaluate("document.querySelectorAll('#robots thead th').length");
  const click = async (index) => {
    const box = await evaluate(`(() => {
      const th = document.querySelectorAll('#robots thead th')[${index}];
      th.scrollIntoView({ block: "center", inline: "center" });
      const r = th.getBoundingClientRect();
      return { x: r.left + r.width / 2, y: r.top + r.height / 2 };
    })()`);
    for (const type of ["mouseMoved", "mousePressed", "mouseReleased"]) {
      await page("Input.dispatchMouseEvent", { type, x: box.x, y: box.y, button: "left", clickCount: 1 });
    }
    return evaluate(`(() => {
      const th = document.querySelectorAll('#robots thead th')[${index}];
      const keys = Array.from(document.querySelectorAll('#robots tbody tr'), (tr) => tr.cells[${index}].dataset.v);
      return { sort: th.getAttribute('aria-sort'), keys };
    })()`);
  };
  const columns = [];
  for (let index = 0; index < count; index++) {
    const [title, type] = await evaluate(`(() => { const th = document.querySelectorAll('#robots thead th')[${index}]; return [th.textContent, th.dataset.type]; })()`);
    const first = await click(index);
    const second = await click(index);
    columns.push({ title, type, first, second });
  }
  finish({ columns, console }, 0);
} catch (error) {
  finish({ error: String(error && error.stack ? error.stack : error) }, 1);
}
