// Runs against the compiled output (npm run compile first): node --test test/
const assert = require("node:assert");
const test = require("node:test");
const { serverCommand } = require("../out/command.js");

test("the server is `urdf_validate server` with the extra arguments after it", () => {
  assert.deepStrictEqual(serverCommand("", []), { command: "urdf_validate", args: ["server"] });
  assert.deepStrictEqual(serverCommand(" /opt/bin/urdf_validate ", ["--package-path", "/ws/src"]), {
    command: "/opt/bin/urdf_validate",
    args: ["server", "--package-path", "/ws/src"],
  });
});
