-- Test driver: open the file given in LOGIXST_PROBE_FILE, wait for diagnostics, ask for
-- completion at LOGIXST_PROBE_LINE/CHAR (0-based) and write both to LOGIXST_PROBE_OUT as JSON.
local file = os.getenv("LOGIXST_PROBE_FILE")
local out = os.getenv("LOGIXST_PROBE_OUT")
local line = tonumber(os.getenv("LOGIXST_PROBE_LINE"))
local char = tonumber(os.getenv("LOGIXST_PROBE_CHAR"))
vim.cmd("edit " .. file)
local buf = vim.api.nvim_get_current_buf()
local got = vim.wait(20000, function() return #vim.diagnostic.get(buf) > 0 end, 50)
local diags = {}
for _, d in ipairs(vim.diagnostic.get(buf)) do
  table.insert(diags, { code = d.code, line = d.lnum, col = d.col, message = d.message })
end
local params = {
  textDocument = { uri = vim.uri_from_bufnr(buf) },
  position = { line = line, character = char },
}
local labels = {}
local responses = vim.lsp.buf_request_sync(buf, "textDocument/completion", params, 20000) or {}
for _, r in pairs(responses) do
  local items = r.result and (r.result.items or r.result) or {}
  for _, item in ipairs(items) do
    table.insert(labels, { label = item.label, detail = item.detail or "" })
  end
end
local fh = io.open(out, "w")
fh:write(vim.fn.json_encode({ waited = got, diagnostics = diags, completion = labels }))
fh:close()
vim.cmd("qall!")
