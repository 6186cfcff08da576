// Loads editors/vscode/extension.js under Node with the two modules only VS Code provides
// replaced by recorders, calls activate(), and prints what the extension asked for: the
// LanguageClient it made (server command, document selector, initialization options).
const Module = require("module");

const made = [];
const settings = JSON.parse(process.env.LOGIXST_SETTINGS || "{}");
const stubs = {
  vscode: {
    workspace: { getConfiguration: (section) => ({ get: (key) => settings[`${section}.${key}`] }) },
  },
  "vscode-languageclient/node": {
    LanguageClient: class {
      constructor(id, name, serverOptions, clientOptions) {
        made.push({ id, name, serverOptions, clientOptions });
        this.started = false;
      }
      start() {
        this.started = true;
        return Promise.resolve();
      }
      stop() {
        return Promise.resolve();
      }
      dispose() {}
    },
  },
};
const load = Module._load;
Module._load = function (request, parent, isMain) {
  if (Object.prototype.hasOwnProperty.call(stubs, request)) {
    return stubs[request];
  }
  return load.call(this, request, parent, isMain);
};

const extension = require(process.argv[2]);
const context = { subscriptions: [] };
Promise.resolve(extension.activate(context)).then(() => {
  const out = { made, subscriptions: context.subscriptions.length };
  out.started = context.subscriptions.every((c) => c.started);
  return Promise.resolve(extension.deactivate()).then(() => console.log(JSON.stringify(out)));
});
