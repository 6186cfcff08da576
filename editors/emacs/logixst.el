;; logixst language server for Logix .st, .rll and .L5X files (Emacs 28 or newer, with eglot).
(require 'eglot)
(define-derived-mode logix-mode prog-mode "Logix"
  "Logix 5000 Structured Text, ladder neutral text and project exports.")
(add-to-list 'auto-mode-alist '("\\.\\(st\\|rll\\|[lL]5[xXkK]\\)\\'" . logix-mode))
(add-to-list 'eglot-server-programs '(logix-mode . ("logixst" "lsp")))
(add-hook 'logix-mode-hook #'eglot-ensure)
