-- Choreonoid Body files in Neovim's built-in LSP client: *.body files get the filetype `body`
-- (YAML syntax, two-space indents), bodyls, the Body-format language server, and :BodyView,
-- which opens the model in bodyview beside the editor.
--
--   vim.opt.runtimepath:append("/path/to/bodyfmt/editors/nvim"); require("bodyls").setup()
--
-- setup{cmd = {"/path/to/bodyls"}} names the server when it is not on PATH; setup{root_dir = DIR}
-- (a folder, or a function of the file's path) replaces the default root; the other fields go to
-- the client as they are (flags = {debounce_text_changes = N}: Neovim 0.7 waits 150 ms before it
-- sends an edit).
-- Works on Neovim 0.7 (Debian 12), which has no vim.lsp.start, and on later versions.
--
-- The editor's own keys then ask bodyls: <C-x><C-o> completes (omnifunc), K shows the hover
-- (a buffer-local mapping, as Neovim 0.10 makes one), <C-]> goes to the definition (tagfunc).
-- Neovim 0.7 sets none of them for a language server, and its vim.lsp.buf.completion()
-- replaces the line from column 1 (it reads the text after the cursor as the word): use
-- <C-x><C-o>, which completes from the start of the server's replace range.
local M = {}

M.config = { cmd = { "bodyls" }, name = "bodyls" }

-- Neovim 0.7: one client per root folder, started once and attached to each buffer.
local clients_by_root = {}

-- The folder a .bodycheck.yaml applies from, else the repository's, else the file's own:
-- bodyls reads the same configuration as bodycheck.
local function root_dir(path)
  local dir = vim.fn.fnamemodify(path, ":p:h")
  local found = vim.fn.findfile(".bodycheck.yaml", dir .. ";")
  if found ~= "" then
    return vim.fn.fnamemodify(found, ":p:h")
  end
  local git = vim.fn.finddir(".git", dir .. ";")
  if git ~= "" then
    return vim.fn.fnamemodify(git, ":p:h:h")
  end
  return dir
end

function M.start(bufnr)
  bufnr = bufnr or vim.api.nvim_get_current_buf()
  -- Everything else set up (cmd, flags, handlers, on_exit...) is the client's configuration.
  local config = vim.tbl_extend("force", {}, M.config)
  local path = vim.api.nvim_buf_get_name(bufnr)
  if type(M.config.root_dir) == "function" then
    config.root_dir = M.config.root_dir(path)
  else
    config.root_dir = M.config.root_dir or root_dir(path)
  end
  if vim.lsp.start then
    return vim.lsp.start(config, { bufnr = bufnr })
  end
  local id = clients_by_root[config.root_dir]
  if not id or not vim.lsp.get_client_by_id(id) then
    id = vim.lsp.start_client(config)
    clients_by_root[config.root_dir] = id
  end
  if id then
    vim.lsp.buf_attach_client(bufnr, id)
  end
  return id
end

-- Has bodyls open the buffer's model in bodyview (its --serve page, which reloads on save); the
-- server answers with the page's URL and asks the editor to show it.
function M.open_viewer(bufnr, on_url)
  bufnr = (bufnr == nil or bufnr == 0) and vim.api.nvim_get_current_buf() or bufnr
  local params = { command = "bodyls.openViewer", arguments = { vim.uri_from_bufnr(bufnr) } }
  vim.lsp.buf_request(bufnr, "workspace/executeCommand", params, function(err, result)
    if err then
      vim.notify("bodyls: " .. err.message, vim.log.levels.ERROR)
    elseif result and result.url then
      vim.notify("bodyview: " .. result.url)
    end
    if on_url then
      on_url(result and result.url, err)
    end
  end)
end

-- Completion, hover and go to definition on the editor's own keys, for the buffer only. A
-- K the user mapped for the buffer stays theirs.
function M.set_keys(bufnr)
  local bo = vim.bo[bufnr]
  bo.omnifunc = "v:lua.vim.lsp.omnifunc"
  bo.tagfunc = "v:lua.vim.lsp.tagfunc"
  if vim.fn.maparg("K", "n", false, true).buffer ~= 1 then
    vim.keymap.set("n", "K", vim.lsp.buf.hover, { buffer = bufnr, desc = "bodyls: hover" })
  end
end

function M.setup(opts)
  M.config = vim.tbl_extend("force", M.config, opts or {})
  local group = vim.api.nvim_create_augroup("bodyls", { clear = true })
  vim.api.nvim_create_autocmd({ "BufRead", "BufNewFile" }, {
    group = group,
    pattern = "*.body",
    callback = function(args)
      vim.bo[args.buf].filetype = "body"
    end,
  })
  vim.api.nvim_create_autocmd("FileType", {
    group = group,
    pattern = "body",
    callback = function(args)
      local bo = vim.bo[args.buf]
      bo.syntax = "yaml"
      bo.commentstring = "# %s"
      bo.expandtab = true
      bo.shiftwidth = 2
      bo.softtabstop = 2
      M.set_keys(args.buf)
      vim.api.nvim_buf_create_user_command(args.buf, "BodyView", function()
        M.open_viewer(args.buf)
      end, { desc = "Open this model in bodyview" })
      M.start(args.buf)
    end,
  })
end

return M
