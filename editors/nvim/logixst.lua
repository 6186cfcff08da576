-- logixst language server for Logix .st, .rll and .L5X files (Neovim 0.7 or newer).
local logixst_client
local function logixst_attach(args)
  local config = { name = "logixst", cmd = { "logixst", "lsp" }, root_dir = vim.fn.getcwd() }
  if vim.lsp.start then
    vim.lsp.start(config, { bufnr = args.buf })
  else
    logixst_client = logixst_client or vim.lsp.start_client(config)
    vim.lsp.buf_attach_client(args.buf, logixst_client)
  end
end
vim.api.nvim_create_autocmd({ "BufReadPost", "BufNewFile" }, {
  pattern = { "*.st", "*.rll", "*.L5X", "*.l5x" },
  callback = logixst_attach,
})
