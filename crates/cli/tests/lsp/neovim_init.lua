-- Headless Neovim with its built-in LSP client attached to `urdf_validate server` (test_neovim.py):
-- opens nothing itself; the test opens the file. Writes what vim.diagnostic.get() shows, as JSON, to
-- $URDF_LSP_OUT once diagnostics arrive (or after 60 s), then quits.
-- vim.lsp.start_client + buf_attach_client: Debian bookworm's Neovim is 0.7, before vim.lsp.start (0.8).
local bin = os.getenv("URDF_VALIDATE_BIN")
local out = os.getenv("URDF_LSP_OUT")

vim.api.nvim_create_autocmd("FileType", {
  pattern = { "xml", "xacro", "urdf" },
  callback = function(args)
    local client = vim.lsp.start_client({
      name = "urdf_validate",
      cmd = { bin, "server" },
      root_dir = vim.fn.fnamemodify(vim.api.nvim_buf_get_name(args.buf), ":h"),
    })
    vim.lsp.buf_attach_client(args.buf, client)
    vim.wait(60000, function() return #vim.diagnostic.get(args.buf) > 0 end, 50)
    local shown = {}
    for _, d in ipairs(vim.diagnostic.get(args.buf)) do
      table.insert(shown, {
        lnum = d.lnum, col = d.col, end_lnum = d.end_lnum, end_col = d.end_col,
        severity = d.severity, message = d.message,
        code = d.code or (d.user_data and d.user_data.lsp and d.user_data.lsp.code),
      })
    end
    local file = assert(io.open(out, "w"))
    file:write(vim.json.encode(shown))
    file:close()
    vim.cmd("qa!")
  end,
})
-- Neovim 0.7 does not know .urdf and .xacro.
vim.cmd("autocmd BufRead,BufNewFile *.urdf,*.xacro setfiletype xml")
